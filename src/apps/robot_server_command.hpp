#pragma once
// `telear robot-server`: the robot service (telear/net/robot_server.hpp) with the driver --driver
// names (sim: the simulated robot; ros1: an arm driven through ROS 1, telear/drivers/
// ros1_robot_driver.hpp, docs/ros.md; ros2: a ros2_control arm over DDS, telear/drivers/
// ros2_robot_driver.hpp, docs/ros2.md), until SIGINT or SIGTERM. The service cannot tell them
// apart: the choice is made here and nowhere else. Prints "robot server listening on HOST:PORT" on
// `out` once it accepts connections (scripts wait for that line; with port 0 it carries the
// ephemeral port), and shuts down cleanly on the signal: streams are ended, the arm stops.
// The log (spdlog, telear/net/server_log.hpp: one line per command with the client's name)
// goes to stderr at --log-level (trace, debug, info, warn, error, off); a bad level exits 2.
// The server is the collision authority (docs/network.md): every trajectory, plan and jog is
// checked for self-collision and, with --workspace FILE, against that workspace, jogs keeping
// --safety-margin metres from its objects.

#include <ostream>
#include <string>

#include "telear/drivers/ros1_robot_driver.hpp"
#include "telear/drivers/ros2_robot_driver.hpp"
#include "telear/geometry/robot_selection.hpp"
#include "telear/net/motion_collision_guard.hpp"

namespace telear::cli {

struct RobotServerCommandOptions : geometry::RobotSelection {
  std::string listen = "127.0.0.1:50051";
  std::string driver = "sim";       // sim | ros1 | ros2
  drivers::Ros1DriverOptions ros;   // --ros-master, --joint-states, --controller, ...
  drivers::Ros2DriverOptions ros2;  // --ros-domain, --ros2-joint-states, --ros2-controller
  std::string token_file;
  bool allow_observers = false;     // reading without any token (--allow-observers)
  std::string observer_token_file;  // a read-only token for watchers
  std::string tls_cert, tls_key;
  int heartbeat_ms = 250;          // default lease heartbeat period
  std::string initial_q;           // sim: joint values or a named configuration; empty: zero
  std::string log_level = "info";  // trace | debug | info | warn | error | off
  std::string workspace;           // workspace YAML; empty: self-collision only
  double safety_margin_m = net::kDefaultSafetyMarginM;
  bool exact_meshes = false;  // mesh links' triangles instead of their parts' convex hulls
};

int run_robot_server(const RobotServerCommandOptions& options, std::ostream& out,
                     std::ostream& err);

}  // namespace telear::cli
