#include "telear/net/robot_server.hpp"

#include <spdlog/spdlog.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <utility>

#include "telear/geometry/workspace_meshes.hpp"
#include "telear/net/bearer_auth.hpp"
#include "telear/net/robot_service.hpp"
#include "telear/net/server_credentials.hpp"
#include "telear/net/token_file.hpp"

namespace telear::net {

namespace {

Result<std::string> read_file(const std::string& path, const char* what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{std::string("cannot read the ") + what + " '" + path + "'"};
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

Status RobotServerOptions::validate() const {
  if (listen_address.empty() || listen_address.rfind(':') == std::string::npos) {
    return Error{"listen_address '" + listen_address + "' is not host:port"};
  }
  if (token.empty() && token_file.empty()) {
    return Error{"no token: give a token file (commands need a bearer token)"};
  }
  if (tls_cert_file.empty() != tls_key_file.empty()) {
    return Error{"TLS needs both a certificate and a key file, got only the " +
                 std::string(tls_cert_file.empty() ? "key" : "certificate")};
  }
  if (max_receive_bytes < 1024) {
    return Error{"max_receive_bytes must be at least 1024, got " +
                 std::to_string(max_receive_bytes)};
  }
  if (!(lease.min_heartbeat_ns > 0 && lease.min_heartbeat_ns <= lease.default_heartbeat_ns &&
        lease.default_heartbeat_ns <= lease.max_heartbeat_ns)) {
    return Error{"lease heartbeat bounds must satisfy 0 < min <= default <= max"};
  }
  if (limits.max_waypoints < 1) return Error{"max_waypoints must be at least 1"};
  if (!(shutdown_deadline_s >= 0.0)) return Error{"shutdown_deadline_s must be >= 0"};
  if (!workspace_file.empty() && !robot_description) {
    return Error{"workspace_file '" + workspace_file +
                 "' needs the robot's description (robot_description) to check against"};
  }
  if (!(safety_margin_m >= 0.0 && safety_margin_m < 1.0)) {
    return Error{"safety_margin_m must be in [0, 1) m, got " + std::to_string(safety_margin_m)};
  }
  return Status::Ok();
}

Result<std::unique_ptr<RobotServer>> RobotServer::create(std::unique_ptr<core::RobotDriver> driver,
                                                         RobotServerOptions options) {
  if (Status s = options.validate(); !s) return Error{"robot server: " + s.error().message};
  std::string token = options.token;
  if (token.empty()) {
    auto loaded = load_token_file(options.token_file);
    if (!loaded) return Error{"robot server: " + loaded.error().message};
    token = std::move(loaded).value();
  }
  std::string observer_token = options.observer_token;
  if (observer_token.empty() && !options.observer_token_file.empty()) {
    auto loaded = load_token_file(options.observer_token_file);
    if (!loaded) return Error{"robot server: observer token: " + loaded.error().message};
    observer_token = std::move(loaded).value();
  }
  if (!observer_token.empty() && constant_time_equal(observer_token, token)) {
    return Error{
        "robot server: the observer token is the operator's token (it must differ: "
        "the observer token only reads)"};
  }
  auto credentials = server_credentials(options.tls_cert_file, options.tls_key_file);
  if (!credentials) return Error{"robot server: " + credentials.error().message};

  std::unique_ptr<MotionCollisionGuard> guard;
  if (options.robot_description) {
    core::Workspace workspace;  // empty: self-collision only
    std::string workspace_yaml;
    if (!options.workspace_file.empty()) {
      auto text = read_file(options.workspace_file, "workspace");
      if (!text) return Error{"robot server: " + text.error().message};
      auto loaded = geometry::load_workspace(options.workspace_file,
                                             options.robot_description->package_paths);
      if (!loaded) return Error{"robot server: " + loaded.error().message};
      workspace = std::move(loaded).value();
      workspace_yaml = std::move(text).value();
    }
    driver->show_workspace(workspace);
    auto made = MotionCollisionGuard::create(*options.robot_description, workspace,
                                             std::move(workspace_yaml), options.safety_margin_m,
                                             options.mesh_collision);
    if (!made) return Error{"robot server: " + made.error().message};
    guard = std::move(made).value();
  }

  std::unique_ptr<RobotServer> server(new RobotServer());
  server->options_ = options;
  server->driver_ = std::move(driver);
  server->service_ = std::make_unique<RobotService>(
      *server->driver_, BearerAuth(token, options.allow_observers, observer_token), options.lease,
      options.limits, std::move(guard));

  grpc::ServerBuilder builder;
  builder.AddListeningPort(options.listen_address, *credentials, &server->port_);
  builder.SetMaxReceiveMessageSize(options.max_receive_bytes);
  builder.RegisterService(server->service_.get());
  server->server_ = builder.BuildAndStart();
  if (!server->server_ || server->port_ == 0) {
    server->service_->begin_shutdown();
    return Error{"robot server: cannot listen on " + options.listen_address +
                 " (address in use, or not an address of this machine)"};
  }
  spdlog::info("robot server listening on {} (driver {}, robot {}, {}, observers {})",
               server->address(), server->driver_->name(), server->driver_->model()->name(),
               options.tls_cert_file.empty() ? "plaintext" : "TLS",
               options.allow_observers  ? "allowed without a token"
               : observer_token.empty() ? "refused"
                                        : "with the observer token");
  return server;
}

RobotServer::~RobotServer() {
  shutdown();
}

std::string RobotServer::address() const {
  const std::string& listen = options_.listen_address;
  return listen.substr(0, listen.rfind(':')) + ":" + std::to_string(port_);
}

void RobotServer::shutdown() {
  if (shut_down_) return;
  shut_down_ = true;
  service_->begin_shutdown();  // ends the streams, so Shutdown need not wait for them
  const auto deadline = std::chrono::system_clock::now() +
                        std::chrono::duration_cast<std::chrono::system_clock::duration>(
                            std::chrono::duration<double>(options_.shutdown_deadline_s));
  server_->Shutdown(deadline);
  server_->Wait();
  driver_->stop("the robot server is shutting down");
  spdlog::info("robot server on {} shut down", address());
}

}  // namespace telear::net
