#pragma once
// RobotServer: the robot service (telear/net/robot_service.hpp) on a gRPC server, with its driver.
//
//   auto server = RobotServer::create(std::move(driver), options);  // listening on return
//   server->port();       // the bound port (options.listen_address may ask for port 0)
//   server->shutdown();   // or destruction
//
// Shutdown: every state stream is ended (UNAVAILABLE, clients reconnect elsewhere or later),
// in-flight unary calls get until shutdown_deadline_s to finish and are cancelled after, the
// lease watchdog stops, and the arm makes a controlled stop. Safe with clients connected.
//
// TLS: with tls_cert_file and tls_key_file (PEM) the port speaks TLS only
// (grpc::SslServerCredentials); without, plaintext (a trusted LAN or loopback). The bearer
// token travels in metadata either way, so over an untrusted network use TLS.

#include <grpcpp/grpcpp.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "telear/core/result.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/core/robot_driver.hpp"
#include "telear/net/lease_manager.hpp"
#include "telear/net/motion_collision_guard.hpp"
#include "telear/net/robot_command_validation.hpp"

namespace telear::net {

class RobotService;

struct RobotServerOptions {
  std::string listen_address = "127.0.0.1:50051";  // host:port; port 0: an ephemeral port
  std::string token;       // the bearer token; when empty, read from token_file
  std::string token_file;  // first line, trimmed (telear/net/bearer_auth.hpp)
  // Reading (info, state, ping) without any token; off: secure by default (bearer_auth.hpp).
  bool allow_observers = false;
  // A read-only token for watchers; when empty, read from observer_token_file (empty: none).
  std::string observer_token;
  std::string observer_token_file;
  std::string tls_cert_file;  // PEM; with tls_key_file: TLS (net/server_credentials.hpp)
  std::string tls_key_file;
  int max_receive_bytes = 4 * 1024 * 1024;  // a larger request is refused by gRPC
  LeaseOptions lease;
  CommandLimits limits;
  double shutdown_deadline_s = 1.0;

  // The collision authority (telear/net/motion_collision_guard.hpp). With the driver's robot
  // description every trajectory, plan and jog is checked for self-collision before motion;
  // with a workspace file (YAML, core/workspace.hpp; it needs the description) also against
  // the workspace, and GetInfo hands the file's text to clients. Neither: no checks.
  std::optional<core::RobotDescription> robot_description;
  std::string workspace_file;
  // Jogs may not bring a link closer than this to a workspace object (m, >= 0).
  double safety_margin_m = kDefaultSafetyMarginM;
  // Mesh links as the convex hulls of their parts (conservative, fast), or kExact: their
  // triangles (docs/collision.md, "Performance"; `telear robot-server --exact-meshes`).
  geometry::MeshCollision mesh_collision = geometry::MeshCollision::kConvexParts;

  // Says which field is wrong and why.
  Status validate() const;
};

class RobotServer {
 public:
  // Loads the token (and TLS files), binds and starts serving. Fails with a message naming
  // the file or address that is wrong.
  static Result<std::unique_ptr<RobotServer>> create(std::unique_ptr<core::RobotDriver> driver,
                                                     RobotServerOptions options);
  ~RobotServer();  // shutdown()
  RobotServer(const RobotServer&) = delete;
  RobotServer& operator=(const RobotServer&) = delete;

  int port() const { return port_; }
  // The listen address with the bound port: "127.0.0.1:43127".
  std::string address() const;
  core::RobotDriver& driver() { return *driver_; }
  const RobotService& service() const { return *service_; }

  // Idempotent; see the header comment.
  void shutdown();

 private:
  RobotServer() = default;

  RobotServerOptions options_;
  std::unique_ptr<core::RobotDriver> driver_;
  std::unique_ptr<RobotService> service_;
  std::unique_ptr<grpc::Server> server_;
  int port_ = 0;
  bool shut_down_ = false;
};

}  // namespace telear::net
