#include "telear/lab/simulated_robot_server.hpp"

#include <utility>

#include "telear/sim/sim_robot_driver.hpp"

namespace telear::lab {

Result<std::unique_ptr<core::RobotDriver>> make_simulated_robot_driver(
    const core::RobotDescription& description, const Eigen::VectorXd& initial_q) {
  sim::SimRobotDriverOptions driver_options;
  driver_options.urdf = core::urdf_text_for_clients(description);
  driver_options.tip_link = description.tip_link;
  if (initial_q.size() > 0) driver_options.robot.initial_q = initial_q;
  auto driver = sim::SimRobotDriver::create(description.model, std::move(driver_options));
  if (!driver) return driver.error();
  return std::unique_ptr<core::RobotDriver>(std::move(driver).value());
}

Result<std::unique_ptr<net::RobotServer>> start_simulated_robot_server(
    const core::RobotDescription& description, SimulatedRobotServerOptions options) {
  net::RobotServerOptions& server = options.server;
  if (options.check_collisions) server.robot_description = description;
  if (options.heartbeat_ns > 0) server.lease.set_default_heartbeat(options.heartbeat_ns);
  auto driver = make_simulated_robot_driver(description, options.initial_q);
  if (!driver) return driver.error();
  return net::RobotServer::create(std::move(driver).value(), server);
}

}  // namespace telear::lab
