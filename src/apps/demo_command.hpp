#pragma once
// `telear demo`: the whole workflow on the embedded default, headless (docs/demo.md).
//
//   1. calibrate the simulated stereo rig from rendered chessboard views and register the
//      robot from its gripper marker (cached in --cache after the first run)
//   2. start the simulated robot server and vision server on loopback (real gRPC)
//   3. connect a session, take the lease
//   4. rehearse a pick-and-place on the ghost over the live stereo video
//   5. preview it (the ghost animates along the plan)
//   6. validate, execute it on the robot as one trajectory, and monitor it; a window of
//      injected video delay (--delay-ms) shows the AR -> VR switch and back
//   7. write the stereo AR video (MP4, side by side), key frames (PNG), report.json and
//      report.md (calibration accuracy, overlay error per eye, fps and latency per stage,
//      bytes sent vs jogging, tracking error, AR/VR switches); the task's recording
//      (OUT/session.mcap unless --record or --no-record) and its plots (`telear report`'s),
//      which report.md shows

#include <cstdint>
#include <ostream>
#include <string>

#include "telear/geometry/robot_selection.hpp"

namespace telear::cli {

// --robot (a shipped robot with a rig, data/rigs/NAME_rig.yaml, or its robot file), --tip,
// --package-path and --missing-meshes as on every command that takes a robot.
struct DemoOptions : geometry::RobotSelection {
  std::string out = "out/demo";
  std::string cache;  // empty: <out>/cache
  std::string resolution = "640x480";
  int delay_ms = 400;  // injected video delay during the execution window; 0: none
  std::uint64_t seed = 1;
  double fps = 15.0;         // the recorded video's (and the display loop's) rate
  double camera_fps = 20.0;  // the simulated cameras' rate
  int live_multisample = 4;  // the live video's MSAA samples per pixel (lab::DemoOptions)
  std::string record;        // the task recorded to this MCAP file; empty: OUT/session.mcap
  bool no_record = false;    // record nothing (then no plots of the recording either)
  bool no_video = false;     // skip the MP4 (key frames and report still written)
};

int run_demo(const DemoOptions& options, std::ostream& out, std::ostream& err);

}  // namespace telear::cli
