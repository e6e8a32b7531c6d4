# The MCAP writer and reader: the writer's byte layout against the specification, error paths
# and statistics (mcap_writer_test.cpp); the reader's round trips, cuts and damage
# (mcap_reader_test.cpp); and its files read by the reference reader, npm's @mcap/core under node
# (mcap_reference_test.cpp runs tests/record/js/read_mcap.mjs; its packages are installed by
# `npm ci --prefix tests/record/js`, which scripts/test.sh runs). A few seconds in all.
find_program(TELEAR_NODE_EXECUTABLE node)
if(NOT TELEAR_NODE_EXECUTABLE)
  # Configured anyway; the reference tests then fail saying node is missing
  # (scripts/install-deps.sh installs it).
  set(TELEAR_NODE_EXECUTABLE /usr/bin/node)
endif()
telear_test(record_mcap_test
  SOURCES mcap_writer_test.cpp mcap_reference_test.cpp mcap_reader_test.cpp
  LIBS telear::record_mcap telear::core nlohmann_json::nlohmann_json)
target_compile_definitions(record_mcap_test PRIVATE
  TELEAR_NODE_EXECUTABLE="${TELEAR_NODE_EXECUTABLE}"
  TELEAR_MCAP_READER_DIR="${CMAKE_CURRENT_SOURCE_DIR}/js")
