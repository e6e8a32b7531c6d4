#pragma once
// Helpers of the robot service tests: a real RobotServer on 127.0.0.1 (ephemeral port) with
// the simulated PUMA 560, raw stubs with or without a token, and a valid trajectory from the
// arm's current state.

#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <string>

#include "telear/core/clock.hpp"
#include "telear/core/trajectory.hpp"
#include "telear/net/robot_server.hpp"
#include "telear/sim/sim_robot_driver.hpp"
#include "telear/v1/robot.grpc.pb.h"
#include "test_util/test_util.hpp"

namespace telear::net::test {

inline constexpr const char* kToken = "s3cret-token";

// Observers allowed (not the default): these tests read state and info with raw stubs and no
// token; the secure default is tested in tls_test.cpp and robot_server_test.cpp.
inline RobotServerOptions server_options(const std::string& listen = "127.0.0.1:0") {
  RobotServerOptions options;
  options.listen_address = listen;
  options.token = kToken;
  options.allow_observers = true;
  options.shutdown_deadline_s = 0.5;
  return options;
}

inline std::unique_ptr<RobotServer> start_server(RobotServerOptions options = server_options()) {
  sim::SimRobotDriverOptions driver_options;
  // Away from the wrist singularity (q5 = 0), so Cartesian jogs are well defined.
  driver_options.robot.initial_q = Eigen::VectorXd::Zero(6);
  driver_options.robot.initial_q << 0.0, 0.5, -0.5, 0.0, 0.5, 0.0;
  auto driver = sim::SimRobotDriver::create(telear::test::puma560(), driver_options);
  EXPECT_TRUE(driver) << driver.error().message;
  auto server = RobotServer::create(std::move(driver).value(), std::move(options));
  EXPECT_TRUE(server) << server.error().message;
  return server ? std::move(server).value() : nullptr;
}

inline std::unique_ptr<v1::RobotService::Stub> stub_for(const RobotServer& server) {
  return v1::RobotService::NewStub(
      grpc::CreateChannel(server.address(), grpc::InsecureChannelCredentials()));
}

// A context with a 2 s deadline and, unless empty, `authorization: Bearer <token>`.
inline std::unique_ptr<grpc::ClientContext> context(const std::string& token = kToken,
                                                    const std::string& name = "test") {
  auto c = std::make_unique<grpc::ClientContext>();
  if (!token.empty()) c->AddMetadata("authorization", "Bearer " + token);
  c->AddMetadata("telear-client", name);
  c->set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(2));
  return c;
}

inline v1::RobotState read_state(v1::RobotService::Stub& stub) {
  // One message of a fresh stream.
  grpc::ClientContext c;
  c.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(2));
  v1::StreamStateRequest request;
  request.set_rate_hz(250);
  auto reader = stub.StreamState(&c, request);
  v1::RobotState state;
  EXPECT_TRUE(reader->Read(&state));
  c.TryCancel();
  reader->Finish();
  return state;
}

// Reads the stream (250 Hz) until `done` says so or `timeout_s` passes; returns the last
// message read.
template <typename Done>
inline v1::RobotState stream_until(v1::RobotService::Stub& stub, Done done,
                                   double timeout_s = 3.0) {
  grpc::ClientContext c;
  c.set_deadline(std::chrono::system_clock::now() +
                 std::chrono::milliseconds(static_cast<int>(timeout_s * 1e3)));
  v1::StreamStateRequest request;
  request.set_rate_hz(250);
  auto reader = stub.StreamState(&c, request);
  v1::RobotState state;
  while (reader->Read(&state)) {
    if (done(state)) break;
  }
  c.TryCancel();
  reader->Finish();
  return state;
}

inline Eigen::VectorXd q_of(const v1::RobotState& state) {
  return Eigen::Map<const Eigen::VectorXd>(state.q().data(), state.q_size());
}

// A trajectory from `q0` by `delta` on every joint and back, timed by core and sampled at
// 50 Hz, as a request (lease and id to fill in).
inline v1::ExecuteTrajectoryRequest trajectory_request(const std::string& id,
                                                       const Eigen::VectorXd& q0, double delta) {
  const Eigen::VectorXd q1 = q0.array() + delta;
  auto trajectory = core::Trajectory::create(*telear::test::puma560(), {{q0}, {q1}, {q0}});
  EXPECT_TRUE(trajectory) << trajectory.error().message;
  auto sampled = trajectory->sampled(50.0);
  EXPECT_TRUE(sampled) << sampled.error().message;
  v1::ExecuteTrajectoryRequest request;
  request.set_trajectory_id(id);
  for (size_t k = 0; k < sampled->times.size(); ++k) {
    v1::Waypoint* w = request.add_waypoints();
    w->set_time_from_start_ns(static_cast<std::int64_t>(std::llround(sampled->times[k] * 1e9)));
    w->mutable_q()->Assign(sampled->q[k].data(), sampled->q[k].data() + sampled->q[k].size());
  }
  return request;
}

inline v1::Lease acquire(v1::RobotService::Stub& stub, const std::string& name = "alice",
                         std::int64_t heartbeat_ns = 5'000'000'000) {
  v1::AcquireLeaseRequest request;
  request.set_client_name(name);
  request.set_heartbeat_period_ns(heartbeat_ns);
  v1::Lease lease;
  const grpc::Status status = stub.AcquireLease(context(kToken, name).get(), request, &lease);
  EXPECT_TRUE(status.ok()) << status.error_message();
  return lease;
}

}  // namespace telear::net::test
