#pragma once
// `telear vision-server`: the stereo vision service (telear/net/vision_server.hpp) on a TCP
// address, from one of four sources, until SIGINT or SIGTERM.
//
//   telear vision-server --listen 127.0.0.1:50052 --source sim [--robot-server HOST:PORT]
//   telear vision-server --source files --left L.avi --right R.avi
//   telear vision-server --source v4l2 --cameras 0,1 --resolution 1280x720
//   telear vision-server --source synthetic --resolution 1280x720 --fps 60
//
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
  std::string source = "sim";                 // sim | files | v4l2 | synthetic
  std::string rig = sim::default_rig_file();  // the shipped rig
  std::string robot_server;                   // HOST:PORT, sim only
  std::string token_file;
  std::string robot_token_file;  // empty: token_file
  std::string left, right;       // files
  std::string cameras = "0,1";   // v4l2
  std::string calibration;       // stereo camera file for GetCameraInfo
  double fps = 0.0;              // 0: the source's default (30; a file's own rate)
  std::string resolution;        // WxH; empty: the source's default
  int quality = 85;
  int supersample = 2;             // sim
  double noise = 1.0;              // sim
  std::string log_level = "info";  // trace | debug | info | warn | error | off
};

int run_vision_server(const VisionServerCommandOptions& options, std::ostream& out,
                      std::ostream& err);

}  // namespace telear::cli
