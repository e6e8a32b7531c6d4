#include "apps/robot_server_command.hpp"

#include <csignal>

#include "apps/command_failure.hpp"
#include "telear/core/joint_values.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/drivers/ros1_robot_driver.hpp"
#include "telear/drivers/ros2_robot_driver.hpp"
#include "telear/lab/simulated_robot_server.hpp"
#include "telear/net/server_log.hpp"

namespace telear::cli {
namespace {

// The one place a driver is chosen (docs/ros.md): the server above it never knows which.
Result<std::unique_ptr<core::RobotDriver>> make_driver(const RobotServerCommandOptions& options,
                                                       const core::RobotDescription& description,
                                                       const Eigen::VectorXd& initial_q) {
  if (options.driver == "sim") return lab::make_simulated_robot_driver(description, initial_q);
  if (options.driver == "ros2") return drivers::make_ros2_robot_driver(description, options.ros2);
  return drivers::make_ros1_robot_driver(description, options.ros);
}

}  // namespace

int run_robot_server(const RobotServerCommandOptions& options, std::ostream& out,
                     std::ostream& err) {
  const CommandFailure fail{err, "telear robot-server"};
  auto log_level = net::parse_log_level(options.log_level);
  if (!log_level) return fail("--log-level " + log_level.error().message, 2);
  if (options.driver != "sim" && options.driver != "ros1" && options.driver != "ros2") {
    return fail("--driver must be sim, ros1 or ros2, got '" + options.driver + "'", 2);
  }
  if (options.driver != "sim" && !options.initial_q.empty()) {
    return fail("--q sets the simulated robot's start; a " + options.driver + " arm is where it is",
                2);
  }
  auto description = core::load_robot_description(options.robot_spec());
  if (!description) return fail(description.error().message, 1);
  Eigen::VectorXd initial_q;
  if (!options.initial_q.empty()) {
    auto q = core::parse_joint_values(*description->model, options.initial_q, "--q", false);
    if (!q) return fail(q.error().message, 1);
    initial_q = *q;
  }
  if (options.heartbeat_ms <= 0) {
    return fail("--heartbeat-ms must be positive, got " + std::to_string(options.heartbeat_ms), 1);
  }
  net::RobotServerOptions server;
  server.lease.set_default_heartbeat(std::int64_t{options.heartbeat_ms} * 1'000'000);
  server.listen_address = options.listen;
  server.token_file = options.token_file;
  server.allow_observers = options.allow_observers;
  server.observer_token_file = options.observer_token_file;
  server.tls_cert_file = options.tls_cert;
  server.tls_key_file = options.tls_key;
  // Collision checking (workspace and self) comes with --workspace: the shipped PUMA's body
  // primitives touch each other at ordinary poses (docs/collision.md, "Known limits"), so
  // self-collision alone would refuse everyday motions of the default robot.
  if (!options.workspace.empty()) server.robot_description = *description;
  server.workspace_file = options.workspace;
  server.safety_margin_m = options.safety_margin_m;
  if (options.exact_meshes) server.mesh_collision = geometry::MeshCollision::kExact;

  // The log (one line per command) goes to stderr: stdout carries only the ready line.
  net::log_to_stderr("robot-server", *log_level);

  // Block the stop signals before any thread starts (the driver's servo, gRPC's pool), so
  // every thread inherits the mask and sigwait below is the one place they arrive.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);

  auto driver = make_driver(options, *description, initial_q);
  if (!driver) return fail(driver.error().message, 1);
  auto started = net::RobotServer::create(std::move(driver).value(), std::move(server));
  if (!started) return fail(started.error().message, 1);
  out << "robot server listening on " << (*started)->address() << std::endl;

  int signal = 0;
  sigwait(&signals, &signal);
  err << "telear robot-server: " << (signal == SIGINT ? "SIGINT" : "SIGTERM")
      << ", shutting down\n";
  (*started)->shutdown();
  return 0;
}

}  // namespace telear::cli
