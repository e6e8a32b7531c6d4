#pragma once
// What `telear web` is started with (docs/web.md): where it listens, the servers behind it and
// the arm it draws. Plain values that the CLI fills; the console's conventions (its
// ConsoleOptions) where the two share a meaning.

#include <string>

#include "telear/console/local_servers.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/geometry/robot_geometry.hpp"

namespace telear::web {

struct WebOptions {
  std::string listen = "127.0.0.1:8080";  // HOST:PORT; port 0: any free port
  // Servers. Empty robot and vision addresses: start local ones with `start_local_servers`
  // (`telear web`: the embedded simulated servers, whose token is printed or given by
  // token_file).
  std::string robot;          // HOST:PORT
  std::string vision;         // HOST:PORT
  std::string token_file;     // the servers' token: the embedded servers', or used to read the
                              // remote vision server's calibration at start
  std::string tls_ca_file;    // the servers speak TLS: trust this CA (PEM)
  std::string tls_cert_file;  // the page over HTTPS: this certificate chain (PEM) ...
  std::string tls_key_file;   // ... and its private key
  std::string calibration;    // registered stereo camera file; empty: the servers' cameras
  console::LocalServersStarter start_local_servers;
  core::RobotSpec arm{"puma560", {}, {}};
  geometry::GeometryOptions geometry;
  std::string workspace;               // empty: the robot's shipped workspace, if any
  std::string resolution = "640x480";  // the video size asked of the vision server
  double lease_heartbeat_s = 0.0;      // 0: the server's default (embedded: 1 s)
  std::string page_root;               // empty: page_files.hpp's search
  // Browser tabs served at once (each holds a session, two streams and a thread): more are
  // answered 503, so that sockets opened by anyone cannot exhaust the machine.
  int max_tabs = 16;
};

}  // namespace telear::web
