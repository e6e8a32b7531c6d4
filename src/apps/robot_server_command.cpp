#include "apps/robot_server_command.hpp"

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "telear/core/joint_values.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/net/robot_server.hpp"
#include "telear/net/server_log.hpp"
#include "telear/sim/sim_robot_driver.hpp"

namespace telear::cli {

int run_robot_server(const RobotServerCommandOptions& options, std::ostream& out,
                     std::ostream& err) {
  auto log_level = net::parse_log_level(options.log_level);
  if (!log_level) {
    err << "telear robot-server: " << log_level.error().message << "\n";
    return 2;
  }
  auto description = core::load_robot_description(options.robot_spec());
  if (!description) {
    err << "telear robot-server: " << description.error().message << "\n";
    return 1;
  }
  const core::RobotModelPtr* model = &description->model;
  sim::SimRobotDriverOptions driver_options;
  driver_options.urdf = core::urdf_text_for_clients(*description);
  driver_options.tip_link = description->tip_link;
  if (!options.initial_q.empty()) {
    auto q = core::parse_joint_values(**model, options.initial_q, "--q", false);
    if (!q) {
      err << "telear robot-server: " << q.error().message << "\n";
      return 1;
    }
    driver_options.robot.initial_q = *q;
  }
  if (options.heartbeat_ms <= 0) {
    err << "telear robot-server: --heartbeat-ms must be positive, got " << options.heartbeat_ms
        << "\n";
    return 1;
  }

  net::RobotServerOptions server_options;
  server_options.listen_address = options.listen;
  server_options.token_file = options.token_file;
  server_options.allow_observers = options.allow_observers;
  server_options.tls_cert_file = options.tls_cert;
  server_options.tls_key_file = options.tls_key;
  // Collision checking (workspace and self) comes with --workspace: the shipped PUMA's body
  // primitives touch each other at ordinary poses (docs/collision.md, "Known limits"), so
  // self-collision alone would refuse everyday motions of the default robot.
  if (!options.workspace.empty()) server_options.robot_description = *description;
  server_options.workspace_file = options.workspace;
  server_options.safety_margin_m = options.safety_margin_m;
  const std::int64_t heartbeat_ns = std::int64_t{options.heartbeat_ms} * 1'000'000;
  server_options.lease.default_heartbeat_ns = heartbeat_ns;
  server_options.lease.min_heartbeat_ns =
      std::min(server_options.lease.min_heartbeat_ns, heartbeat_ns);
  server_options.lease.max_heartbeat_ns =
      std::max(server_options.lease.max_heartbeat_ns, heartbeat_ns);

  // The log (one line per command) goes to stderr: stdout carries only the ready line.
  net::log_to_stderr("robot-server", *log_level);

  // Block the stop signals before any thread starts (the driver's servo, gRPC's pool), so
  // every thread inherits the mask and sigwait below is the one place they arrive.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);

  auto driver = sim::SimRobotDriver::create(*model, std::move(driver_options));
  if (!driver) {
    err << "telear robot-server: " << driver.error().message << "\n";
    return 1;
  }
  auto server = net::RobotServer::create(std::move(driver).value(), server_options);
  if (!server) {
    err << "telear robot-server: " << server.error().message << "\n";
    return 1;
  }
  out << "robot server listening on " << (*server)->address() << std::endl;

  int signal = 0;
  sigwait(&signals, &signal);
  err << "telear robot-server: " << (signal == SIGINT ? "SIGINT" : "SIGTERM")
      << ", shutting down\n";
  (*server)->shutdown();
  return 0;
}

}  // namespace telear::cli
