#pragma once
// `telear robot-server`'s server as a library call: the robot service
// (telear/net/robot_server.hpp) with the simulated robot (telear/sim/sim_robot_driver.hpp) as
// its driver, serving the description's URDF and tip on GetInfo so that a client draws the
// same arm. The embedded servers of the demo and the console (embedded_servers.hpp) start
// the same pair on loopback beside a simulated rig.

#include <Eigen/Core>
#include <cstdint>
#include <memory>

#include "telear/core/result.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/core/robot_driver.hpp"
#include "telear/net/robot_server.hpp"

namespace telear::lab {

struct SimulatedRobotServerOptions {
  net::RobotServerOptions server;  // address, token, observers, TLS, workspace, safety margin
  Eigen::VectorXd initial_q;       // empty: the simulated robot's default
  // > 0: the lease's default heartbeat period, its bounds widened to admit it when outside.
  std::int64_t heartbeat_ns = 0;
  // Every motion checked for collisions against the robot's description (and the server's
  // workspace file); off, no collision checks (docs/collision.md, "Known limits").
  bool check_collisions = false;
};

// The simulated robot as a driver: the description's arm at initial_q (empty: its default),
// reporting the description's URDF and tip on GetInfo. Errors: the simulated robot's.
Result<std::unique_ptr<core::RobotDriver>> make_simulated_robot_driver(
    const core::RobotDescription& description, const Eigen::VectorXd& initial_q);

// Errors: the simulated robot's (initial_q outside the limits, ...) and the server's (the
// address in use, TLS files, the workspace file, ...).
Result<std::unique_ptr<net::RobotServer>> start_simulated_robot_server(
    const core::RobotDescription& description, SimulatedRobotServerOptions options);

}  // namespace telear::lab
