# record: the session recorder over the network clients (net) and the two libraries above.
telear_library(record server_recorder.cpp session_recorder.cpp)
target_link_libraries(telear_record PUBLIC telear::record_mcap telear::record_schemas telear::net
                                           telear::core)
