# The session recorder against real servers on loopback (a simulated PUMA, a synthetic stereo
# source), its file decoded by the reference reader with the file's own schemas
# (js/decode_recording.mjs, the packages `npm ci --prefix tests/record/js` installs). ~3 s.
# RecordingSeries reads back a recording with known content (synthetic_recording.hpp);
# RecordingPlayback one with decodable frames, a calibration, the view's ghost and AR/VR events.
telear_test(record_test
  SOURCES session_recorder_test.cpp recording_series_test.cpp recording_playback_test.cpp
  LIBS telear::record telear::sim_robot nlohmann_json::nlohmann_json
  PCH net)
target_compile_definitions(record_test PRIVATE TELEAR_RECORD_JS_DIR="${CMAKE_CURRENT_SOURCE_DIR}/js")
# RecordCli runs the telear binary.
target_compile_definitions(record_test PRIVATE TELEAR_BINARY="$<TARGET_FILE:telear>")
add_dependencies(record_test telear)
