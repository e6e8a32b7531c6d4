#include "telear/lab/simulated_robot_server.hpp"

#include <algorithm>
#include <utility>

#include "telear/sim/sim_robot_driver.hpp"

namespace telear::lab {

Result<std::unique_ptr<net::RobotServer>> start_simulated_robot_server(
    const core::RobotDescription& description, SimulatedRobotServerOptions options) {
  sim::SimRobotDriverOptions driver_options;
  driver_options.urdf = core::urdf_text_for_clients(description);
  driver_options.tip_link = description.tip_link;
  if (options.initial_q.size() > 0) driver_options.robot.initial_q = options.initial_q;
  net::RobotServerOptions& server = options.server;
  if (options.check_collisions) server.robot_description = description;
  if (options.heartbeat_ns > 0) {
    net::LeaseOptions& lease = server.lease;
    lease.default_heartbeat_ns = options.heartbeat_ns;
    lease.min_heartbeat_ns = std::min(lease.min_heartbeat_ns, options.heartbeat_ns);
    lease.max_heartbeat_ns = std::max(lease.max_heartbeat_ns, options.heartbeat_ns);
  }
  auto driver = sim::SimRobotDriver::create(description.model, std::move(driver_options));
  if (!driver) return driver.error();
  return net::RobotServer::create(std::move(driver).value(), server);
}

}  // namespace telear::lab
