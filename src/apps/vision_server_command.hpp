#pragma once
// `telear vision-server`: the stereo vision service (telear/net/vision_server.hpp) on a TCP
// address, from one of five sources, until SIGINT or SIGTERM.
//
//   telear vision-server --listen 127.0.0.1:50052 --source sim [--robot-server HOST:PORT]
//   telear vision-server --source files --left L.avi --right R.avi
//   telear vision-server --source v4l2 --cameras 0,1 --resolution 1280x720
//   telear vision-server --source synthetic --resolution 1280x720 --fps 60
//   telear vision-server --source ros --left /stereo/left/image_raw --right /stereo/right/image_raw
//                        [--ros-master http://HOST:11311] [--sync-tolerance-ms 20]
//
// The ros source (docs/ros.md, "Cameras") serves the calibration its cameras' camera_info
// states, unless --calibration names a file; its --fps is only the rate reported (0: measured).
// With --robot-server the simulated rig follows that robot server's state stream (the arm in
// the video moves with the robot). --token-file makes every call need the token, and is also
// presented to the robot server (unless --robot-token-file names another). Prints
// "vision server listening on HOST:PORT" once it accepts calls (port 0: an ephemeral port,
// printed). The log (spdlog, telear/net/server_log.hpp: one line per client stream with the
// client's name, errors) goes to stderr at --log-level (trace, debug, info, warn, error, off).
// Exit codes: 0 after a signal, 2 bad options, 1 the server could not start.

#include <ostream>
#include <string>

#include "telear/sim/stereo_rig.hpp"

namespace telear::cli {

struct VisionServerCommandOptions {
  std::string listen = "127.0.0.1:50052";
  std::string source = "sim";                 // sim | files | v4l2 | synthetic | ros
  std::string rig = sim::default_rig_file();  // the shipped rig
  std::string robot_server;                   // HOST:PORT, sim only
  std::string token_file;
  std::string robot_token_file;     // empty: token_file
  std::string observer_token_file;  // a second, read-only token (net/bearer_auth.hpp)
  std::string tls_cert, tls_key;    // TLS (PEM)
  std::string left, right;          // files; ros: the image topics
  std::string cameras = "0,1";      // v4l2
  std::string calibration;          // stereo camera file for GetCameraInfo
  double fps = 0.0;                 // 0: the source's default (30; a file's own rate)
  std::string resolution;           // WxH; empty: the source's default
  int quality = 85;
  int supersample = 2;             // sim
  double noise = 1.0;              // sim
  bool frame_code = false;         // sim, synthetic: stamp the frame code (docs/latency.md)
  std::string log_level = "info";  // trace | debug | info | warn | error | off
  // ros: the master (http://HOST:PORT; empty: $ROS_MASTER_URI) and the largest stamp
  // difference of a left-right pair
  std::string ros_master;
  double sync_tolerance_ms = 20.0;
};

int run_vision_server(const VisionServerCommandOptions& options, std::ostream& out,
                      std::ostream& err);

}  // namespace telear::cli
