#pragma once
// `telear demo` as a library call (docs/demo.md): the operator's whole workflow on the
// embedded simulated robot and stereo rig, headless, in seven numbered steps:
//
//   1. calibrate the stereo rig (include/telear/lab/calibration_pipeline.hpp, cached)
//   2. start the simulated robot and vision servers on loopback (embedded_servers.hpp), and
//      register the robot from images captured through them (registration_capture.hpp,
//      vision/capture_registration.hpp), measured against the simulator's truth; then
//      restart them at the ready pose for the task (the live view's cheaper rendering)
//   3. connect a session::Session, open the AR view and the recorder (session_recorder.hpp)
//   4-6. the task (include/telear/lab/demo_task.hpp)
//   7. the report (include/telear/lab/demo_report.hpp)
//
// Blocks for the whole run (tens of seconds; minutes when the calibration is not cached) on
// the calling thread, which gets the headless OpenGL context.

#include <cstdint>
#include <string>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/geometry/robot_geometry.hpp"
#include "telear/lab/demo_task.hpp"

namespace telear::lab {

struct DemoOptions {
  std::string out_dir = "out/demo";
  std::string cache_dir;               // empty: <out_dir>/cache
  std::string robot = "puma560";       // a robot with a rig: puma560, ur6, arm7 or their files
  std::string tip;                     // the tip link when the URDF tree has several leaves
  geometry::GeometryOptions geometry;  // --package-path, --missing-meshes
  std::string rig_file;                // empty: the data directory's rigs/<robot>_rig.yaml
  int width = 640;                     // the operator's view per eye, px
  int height = 480;
  int delay_ms = 400;  // injected video delay during the execution window, 0..5000
  std::uint64_t seed = 1;
  double fps = 15.0;         // the recorded video's (and the display loop's) rate, 1..60
  double camera_fps = 20.0;  // the simulated cameras' rate
  bool video = true;         // false: no MP4 (key frames and report still written)
  // Registration through the servers (step 2): automatic capture poses and frames per pose,
  // and the simulated cameras' anti-aliasing while capturing (the marker's corners are found
  // to ~0.1 px; the task's servers render at 1).
  int registration_poses = 16;  // 4..200
  int registration_frames = 2;  // 1..30
  int supersample = 2;          // 1..8
  // The simulated cameras' MSAA samples per pixel (sim::SceneOptions::multisample), 1..16,
  // for the task's live video and, on top of `supersample`, for the registration capture.
  // Point sampling (1) puts the marker's edges on a staircase of whole pixels and the live
  // marker residual at ~0.45 px where the overlay itself is off by ~0.1 (docs/demo.md); 2 x 2
  // supersampling alone, on a staircase of half pixels (issue 26 item 1).
  int live_multisample = 4;
  // The task's session recorded to this MCAP file (record::ServerRecorder: the servers'
  // streams, the session's events), then plotted into out_dir by report::write_recording_report
  // (its PNGs and recording_report.md, which report.md shows); empty: no recording, no plots.
  // (`telear demo` gives OUT/session.mcap unless --record or --no-record.)
  std::string record_path;

  // Errors name the option as the CLI spells it and its range.
  Status validate() const;
};

struct DemoOutcome {
  std::string execution_result;  // "completed" when the plan ran to its end
  std::string report_md;         // paths
  std::string report_json;
  std::string video_path;  // empty: no video
  std::string video_codec;
  std::string video_warning;  // H.264 unavailable: mp4v used
  std::vector<std::string> key_frames;
  bool calibration_cached = false;
  double seconds = 0.0;
};

Result<DemoOutcome> run_demo(const DemoOptions& options, const DemoProgress& progress = {});

}  // namespace telear::lab
