# record: the session recorder over the network clients (net) and the two libraries above.
# recording_series: a recording read back as time series (telear report, telear replay);
# recording_playback: what the view showed at a time (telear replay).
telear_library(record recording_playback.cpp recording_series.cpp server_recorder.cpp
               session_recorder.cpp)
target_link_libraries(telear_record PUBLIC telear::record_mcap telear::record_schemas telear::net
                                           telear::core)
