#pragma once
// What `telear console` is started with (docs/console.md). Plain values that the CLI fills,
// and how local servers are started when no address is given.

#include <string>

#include "telear/console/local_servers.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/geometry/robot_geometry.hpp"

namespace telear::console {

struct ConsoleOptions {
  // Servers. Empty robot and vision addresses: start local ones with `start_local_servers`
  // (`telear console`: the embedded simulated servers).
  std::string robot;        // HOST:PORT
  std::string vision;       // HOST:PORT
  std::string token_file;   // first line: the bearer token
  std::string tls_ca_file;  // the servers speak TLS: trust this CA (PEM); empty: plaintext
  std::string calibration;  // registered stereo camera file; empty: see docs/console.md
  LocalServersStarter start_local_servers;  // empty: the addresses are required
  // The arm drawn as the ghost (--arm, --tip, --package-path, --missing-meshes): the same
  // robot the robot server runs; the embedded servers simulate it.
  core::RobotSpec arm{"puma560", {}, {}};
  geometry::GeometryOptions geometry;
  // The operator's copy of the scene (drawn in the AR and VR views); empty: the robot's
  // shipped workspace (core::default_workspace_file), none when it has no such file.
  std::string workspace;
  std::string resolution = "640x480";  // the video size asked of the vision server
  // The lease's heartbeat period asked of the robot server (SessionOptions::lease_heartbeat_s);
  // 0: the server's default (the embedded servers: 1 s).
  double lease_heartbeat_s = 0.0;

  // Output.
  int width = 1600, height = 1000;  // window (or headless frame buffer) size
  bool headless = false;            // EGL frame buffer, no window, no X server
  std::string fullscreen_eyes;      // "", "two-windows" or "sbs" (head-mounted / 3-D display)
  // The video decoded to Y'CbCr planes and converted on the GPU ("on"), to RGB on the CPU
  // ("off"), or "auto": planes where the renderer is a hardware GPU.
  std::string video_planes = "auto";
  std::string screenshot;  // write the console's image here after `frames` frames
  int frames = 0;          // > 0: stop after this many frames (and the script)
  std::string script;      // UI actions to replay (ui_script.hpp)
  double max_fps = 60.0;   // frame pacing when there is no vsync (headless)
  // Record the session to this MCAP file (record::ServerRecorder on the servers the console
  // starts with, the session's events; docs/recording.md); empty: no recording.
  std::string record;
};

}  // namespace telear::console
