#include "apps/robot_server_command.hpp"

#include <csignal>

#include "apps/command_failure.hpp"
#include "telear/core/joint_values.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/lab/simulated_robot_server.hpp"
#include "telear/net/server_log.hpp"

namespace telear::cli {

int run_robot_server(const RobotServerCommandOptions& options, std::ostream& out,
                     std::ostream& err) {
  const CommandFailure fail{err, "telear robot-server"};
  auto log_level = net::parse_log_level(options.log_level);
  if (!log_level) return fail("--log-level " + log_level.error().message, 2);
  auto description = core::load_robot_description(options.robot_spec());
  if (!description) return fail(description.error().message, 1);
  lab::SimulatedRobotServerOptions server_options;
  if (!options.initial_q.empty()) {
    auto q = core::parse_joint_values(*description->model, options.initial_q, "--q", false);
    if (!q) return fail(q.error().message, 1);
    server_options.initial_q = *q;
  }
  if (options.heartbeat_ms <= 0) {
    return fail("--heartbeat-ms must be positive, got " + std::to_string(options.heartbeat_ms), 1);
  }
  server_options.heartbeat_ns = std::int64_t{options.heartbeat_ms} * 1'000'000;
  net::RobotServerOptions& server = server_options.server;
  server.listen_address = options.listen;
  server.token_file = options.token_file;
  server.allow_observers = options.allow_observers;
  server.tls_cert_file = options.tls_cert;
  server.tls_key_file = options.tls_key;
  // Collision checking (workspace and self) comes with --workspace: the shipped PUMA's body
  // primitives touch each other at ordinary poses (docs/collision.md, "Known limits"), so
  // self-collision alone would refuse everyday motions of the default robot.
  server_options.check_collisions = !options.workspace.empty();
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

  auto started = lab::start_simulated_robot_server(*description, std::move(server_options));
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
