// The robot server as the safety authority, over real gRPC on loopback: authentication,
// the lease and its dead-man, validation before motion, duplicate ids, jog expiry, e-stop.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "robot_test_support.hpp"
#include "telear/net/robot_service.hpp"

namespace telear::net::test {
namespace {

using ::testing::HasSubstr;

TEST(RobotServer, StreamsStateAtTheRequestedRate) {
  auto server = start_server();
  auto stub = stub_for(*server);
  grpc::ClientContext c;
  v1::StreamStateRequest request;
  request.set_rate_hz(100);
  auto reader = stub->StreamState(&c, request);
  v1::RobotState state;
  std::vector<std::int64_t> capture;
  std::uint64_t sequence = 0;
  while (capture.size() < 21 && reader->Read(&state)) {
    EXPECT_EQ(state.sequence(), sequence + 1);
    sequence = state.sequence();
    EXPECT_EQ(state.q_size(), 6);
    EXPECT_EQ(state.mode(), v1::ROBOT_MODE_IDLE);
    EXPECT_GE(state.server_send_ns(), state.capture_ns());
    capture.push_back(state.capture_ns());
  }
  c.TryCancel();
  reader->Finish();
  ASSERT_EQ(capture.size(), 21u);
  // 20 periods of 10 ms, paced by the server: the mean is the rate whatever the jitter.
  const double mean_period_s = core::ns_to_s(capture.back() - capture.front()) / 20.0;
  EXPECT_NEAR(mean_period_s, 0.010, 0.004);

  grpc::ClientContext too_fast;
  request.set_rate_hz(1000);
  auto refused = stub->StreamState(&too_fast, request);
  EXPECT_FALSE(refused->Read(&state));
  const grpc::Status status = refused->Finish();
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(status.error_message(), HasSubstr("outside 1..250 Hz"));
}

TEST(RobotServer, InfoDescribesTheRobot) {
  auto server = start_server();
  auto stub = stub_for(*server);
  v1::RobotInfo info;
  // An observer (no token) may read.
  ASSERT_TRUE(stub->GetInfo(context("").get(), v1::GetInfoRequest(), &info).ok());
  EXPECT_EQ(info.model_name(), "puma560");
  EXPECT_EQ(info.driver(), "simulated");
  ASSERT_EQ(info.joints_size(), 6);
  EXPECT_EQ(info.joints(1).name(), "shoulder");
  EXPECT_EQ(info.heartbeat_period_ns(), 250'000'000);
  EXPECT_GT(info.max_waypoints(), 0);
}

TEST(RobotServer, RefusesMissingOrWrongTokensAndObserverCommands) {
  auto server = start_server();
  auto stub = stub_for(*server);
  v1::AcquireLeaseRequest request;
  request.set_client_name("mallory");
  v1::Lease lease;
  grpc::Status status = stub->AcquireLease(context("").get(), request, &lease);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_THAT(status.error_message(), HasSubstr("no token"));
  status = stub->AcquireLease(context("wrong-token").get(), request, &lease);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_THAT(status.error_message(), HasSubstr("wrong token"));
  // An observer may not even stop the arm: EStop needs authentication (any valid token).
  v1::EStopResponse estop;
  status = stub->EStop(context("").get(), v1::EStopRequest(), &estop);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_FALSE(read_state(*stub).estop());
  // A wrong token is refused even for reading.
  v1::RobotInfo info;
  status = stub->GetInfo(context("wrong-token").get(), v1::GetInfoRequest(), &info);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::UNAUTHENTICATED);
}

TEST(RobotServer, WithoutObserversStateNeedsTheToken) {
  RobotServerOptions options = server_options();
  options.allow_observers = false;
  auto server = start_server(options);
  auto stub = stub_for(*server);
  v1::RobotInfo info;
  const grpc::Status status = stub->GetInfo(context("").get(), v1::GetInfoRequest(), &info);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_THAT(status.error_message(), HasSubstr("does not allow observers"));
  EXPECT_TRUE(stub->GetInfo(context().get(), v1::GetInfoRequest(), &info).ok());
}

TEST(RobotServer, OneOperatorHoldsTheLease) {
  auto server = start_server();
  auto stub = stub_for(*server);
  const v1::Lease alice = acquire(*stub, "alice");
  EXPECT_EQ(alice.lease_id().size(), 32u);
  EXPECT_EQ(alice.heartbeat_period_ns(), 5'000'000'000);

  v1::AcquireLeaseRequest request;
  request.set_client_name("bob");
  v1::Lease bob;
  grpc::Status status = stub->AcquireLease(context(kToken, "bob").get(), request, &bob);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::PERMISSION_DENIED);
  EXPECT_THAT(status.error_message(), HasSubstr("the lease is held by 'alice'"));

  // Commands without the lease are refused, with or without a made-up id.
  v1::JogRequest jog;
  jog.set_lease_id("not-a-lease");
  jog.set_expires_ns(core::monotonic_ns() + 500'000'000);
  jog.mutable_joint_increment()->set_delta(0.01);
  v1::JogResponse response;
  status = stub->Jog(context(kToken, "bob").get(), jog, &response);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::PERMISSION_DENIED);
  EXPECT_THAT(status.error_message(), HasSubstr("held by 'alice'"));
  EXPECT_EQ(read_state(*stub).lease_holder(), "alice");

  v1::ReleaseLeaseRequest release;
  release.set_lease_id(alice.lease_id());
  v1::ReleaseLeaseResponse released;
  ASSERT_TRUE(stub->ReleaseLease(context().get(), release, &released).ok());
  acquire(*stub, "bob");
}

TEST(RobotServer, HeartbeatIsClampedToTheServerBounds) {
  auto server = start_server();
  auto stub = stub_for(*server);
  const v1::Lease lease = acquire(*stub, "alice", 1'000);  // 1 us: far below the minimum
  EXPECT_EQ(lease.heartbeat_period_ns(), LeaseOptions().min_heartbeat_ns);
}

TEST(RobotServer, LapsedLeaseStopsTheArmWithinTheBound) {
  auto server = start_server();
  auto stub = stub_for(*server);
  const v1::Lease lease = acquire(*stub, "alice", 100'000'000);  // 100 ms, never renewed
  v1::JogRequest jog;
  jog.set_lease_id(lease.lease_id());
  jog.set_expires_ns(core::monotonic_ns() + 5'000'000'000);  // the jog itself would run for 5 s
  jog.mutable_joint_velocity()->mutable_qd()->Add(0.5);
  for (int j = 1; j < 6; ++j) jog.mutable_joint_velocity()->mutable_qd()->Add(0.0);
  v1::JogResponse response;
  const grpc::Status status = stub->Jog(context().get(), jog, &response);
  ASSERT_TRUE(status.ok()) << status.error_message();

  const v1::RobotState stopping = stream_until(*stub, [](const v1::RobotState& s) {
    return s.mode() == v1::ROBOT_MODE_STOPPING || s.mode() == v1::ROBOT_MODE_IDLE;
  });
  ASSERT_TRUE(stopping.mode() == v1::ROBOT_MODE_STOPPING || stopping.mode() == v1::ROBOT_MODE_IDLE);
  if (stopping.mode() == v1::ROBOT_MODE_STOPPING) {
    EXPECT_THAT(stopping.stop_reason(), HasSubstr("the lease of 'alice' lapsed"));
  }
  // The stop began within the dead-man's 200 ms of the expiry, as the server recorded it...
  const auto lapse = server->service().lease().last_lapse();
  ASSERT_TRUE(lapse.has_value());
  EXPECT_EQ(lapse->holder, "alice");
  EXPECT_EQ(lapse->expired_ns, lease.expires_ns());
  EXPECT_LT(lapse->stop_started_ns - lapse->expired_ns, 200'000'000);
  // ... and as the state stream saw it (the first non-jogging state, at 250 Hz).
  EXPECT_LT(stopping.capture_ns() - lease.expires_ns(), 200'000'000);
  const v1::RobotState idle =
      stream_until(*stub, [](const v1::RobotState& s) { return s.mode() == v1::ROBOT_MODE_IDLE; });
  EXPECT_EQ(idle.mode(), v1::ROBOT_MODE_IDLE);
  EXPECT_EQ(idle.qd(0), 0.0);
  EXPECT_EQ(idle.lease_holder(), "");

  // The lapsed holder is told why its commands fail.
  v1::JogResponse again;
  jog.set_expires_ns(core::monotonic_ns() + 500'000'000);
  const grpc::Status refused = stub->Jog(context().get(), jog, &again);
  EXPECT_EQ(refused.error_code(), grpc::StatusCode::PERMISSION_DENIED);
  EXPECT_THAT(refused.error_message(), HasSubstr("lapsed"));
}

TEST(RobotServer, InvalidTrajectoriesAreRejectedWithTheReasonAndNoMotion) {
  auto server = start_server();
  auto stub = stub_for(*server);
  const v1::Lease lease = acquire(*stub);
  const v1::RobotState before = read_state(*stub);
  const Eigen::VectorXd q0 = q_of(before);

  struct Case {
    const char* name;
    v1::ExecuteTrajectoryRequest request;
    const char* reason;
  };
  std::vector<Case> cases;
  {
    auto r = trajectory_request("nan", q0, 0.1);
    r.mutable_waypoints(3)->set_q(2, std::numeric_limits<double>::quiet_NaN());
    cases.push_back({"NaN", r, "not a finite number"});
  }
  {
    auto r = trajectory_request("limits", q0, 0.1);
    r.mutable_waypoints(3)->set_q(1, 2.5);  // shoulder at 143 deg, beyond its 110 deg limit
    cases.push_back({"over the limits", r, "beyond its upper limit"});
  }
  {
    auto r = trajectory_request("fast", q0, 0.1);
    for (auto& w : *r.mutable_waypoints()) w.set_time_from_start_ns(w.time_from_start_ns() / 10);
    cases.push_back({"too fast", r, "beyond its max velocity"});
  }
  {
    Eigen::VectorXd off = q0;
    off[1] += 0.12;
    cases.push_back({"start far off", trajectory_request("p1", off, 0.05),
                     "starts 0.120 rad (6.88 deg) from the current state at joint 2 (shoulder) "
                     "(tolerance 0.010 rad)"});
  }
  {
    v1::ExecuteTrajectoryRequest r = trajectory_request("many", q0, 0.1);
    while (r.waypoints_size() <= 10000) *r.add_waypoints() = r.waypoints(0);
    cases.push_back({"too many waypoints", r, "more than the maximum of 10000"});
  }
  {
    auto r = trajectory_request(std::string(129, 'x'), q0, 0.1);
    cases.push_back({"id too long", r, "more than the maximum of 128"});
  }
  for (Case& c : cases) {
    SCOPED_TRACE(c.name);
    c.request.set_lease_id(lease.lease_id());
    v1::ExecuteTrajectoryResponse response;
    const grpc::Status status = stub->ExecuteTrajectory(context().get(), c.request, &response);
    EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
    EXPECT_THAT(status.error_message(), HasSubstr(c.reason));
  }
  const v1::RobotState after = read_state(*stub);
  EXPECT_EQ(after.mode(), v1::ROBOT_MODE_IDLE);
  EXPECT_EQ(after.last_trajectory_id(), "");
  EXPECT_TRUE(q_of(after).isApprox(q0, 0.0)) << q_of(after).transpose();

  // A rejected id is not remembered: the same id, valid now, is accepted.
  auto valid = trajectory_request("p1", q0, 0.02);
  valid.set_lease_id(lease.lease_id());
  v1::ExecuteTrajectoryResponse response;
  const grpc::Status status = stub->ExecuteTrajectory(context().get(), valid, &response);
  EXPECT_TRUE(status.ok()) << status.error_message();
  EXPECT_FALSE(response.duplicate());
}

TEST(RobotServer, TooLargeMessageIsRefusedByTheTransport) {
  RobotServerOptions options = server_options();
  options.max_receive_bytes = 64 * 1024;
  auto server = start_server(options);
  auto stub = stub_for(*server);
  const v1::Lease lease = acquire(*stub);
  auto r = trajectory_request("big", q_of(read_state(*stub)), 0.1);
  while (r.ByteSizeLong() < 128 * 1024) *r.add_waypoints() = r.waypoints(0);
  r.set_lease_id(lease.lease_id());
  v1::ExecuteTrajectoryResponse response;
  const grpc::Status status = stub->ExecuteTrajectory(context().get(), r, &response);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(read_state(*stub).mode(), v1::ROBOT_MODE_IDLE);
}

TEST(RobotServer, DuplicateTrajectoryIdIsExecutedOnce) {
  auto server = start_server();
  auto stub = stub_for(*server);
  const v1::Lease lease = acquire(*stub);
  const Eigen::VectorXd q0 = q_of(read_state(*stub));
  auto request = trajectory_request("pick-1", q0, 0.05);
  request.set_lease_id(lease.lease_id());
  v1::ExecuteTrajectoryResponse first, second;
  ASSERT_TRUE(stub->ExecuteTrajectory(context().get(), request, &first).ok());
  EXPECT_FALSE(first.duplicate());
  EXPECT_EQ(first.status(), v1::TRAJECTORY_STATUS_RUNNING);
  // A retry (the reply was "lost") while it runs: the first acceptance, nothing new.
  ASSERT_TRUE(stub->ExecuteTrajectory(context().get(), request, &second).ok());
  EXPECT_TRUE(second.duplicate());
  EXPECT_EQ(second.accepted_ns(), first.accepted_ns());
  EXPECT_DOUBLE_EQ(second.duration_s(), first.duration_s());

  const v1::RobotState done = stream_until(
      *stub, [](const v1::RobotState& s) { return s.last_trajectory_id() == "pick-1"; });
  EXPECT_EQ(done.last_trajectory_status(), v1::TRAJECTORY_STATUS_COMPLETED);
  // Once done, a retry is still the duplicate (with its status) and does not move the arm.
  v1::ExecuteTrajectoryResponse third;
  ASSERT_TRUE(stub->ExecuteTrajectory(context().get(), request, &third).ok());
  EXPECT_TRUE(third.duplicate());
  EXPECT_EQ(third.status(), v1::TRAJECTORY_STATUS_COMPLETED);
  EXPECT_EQ(read_state(*stub).mode(), v1::ROBOT_MODE_IDLE);
}

TEST(RobotServer, JogPastItsExpiryIsIgnored) {
  auto server = start_server();
  auto stub = stub_for(*server);
  const v1::Lease lease = acquire(*stub);
  const Eigen::VectorXd q0 = q_of(read_state(*stub));
  v1::JogRequest jog;
  jog.set_lease_id(lease.lease_id());
  jog.set_expires_ns(core::monotonic_ns() - 20'000'000);  // expired 20 ms ago
  jog.mutable_joint_increment()->set_joint(0);
  jog.mutable_joint_increment()->set_delta(0.1);
  v1::JogResponse response;
  const grpc::Status status = stub->Jog(context().get(), jog, &response);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(status.error_message(), HasSubstr("jog ignored: it expired"));
  const v1::RobotState after = read_state(*stub);
  EXPECT_EQ(after.mode(), v1::ROBOT_MODE_IDLE);
  EXPECT_TRUE(q_of(after).isApprox(q0, 0.0));

  // In time, the same jog moves the arm to q0 + 0.1 on the waist.
  jog.set_expires_ns(core::monotonic_ns() + 2'000'000'000);
  ASSERT_TRUE(stub->Jog(context().get(), jog, &response).ok());
  ASSERT_EQ(response.target_q_size(), 6);
  EXPECT_NEAR(response.target_q(0), q0[0] + 0.1, 1e-12);
}

TEST(RobotServer, EStopLatchesUntilReset) {
  auto server = start_server();
  auto stub = stub_for(*server);
  const v1::Lease lease = acquire(*stub, "alice");
  v1::JogRequest jog;
  jog.set_lease_id(lease.lease_id());
  jog.set_expires_ns(core::monotonic_ns() + 2'000'000'000);
  jog.mutable_joint_increment()->set_joint(0);
  jog.mutable_joint_increment()->set_delta(0.3);
  v1::JogResponse jogged;
  ASSERT_TRUE(stub->Jog(context().get(), jog, &jogged).ok());

  // Bob has a token but no lease: he may stop the arm all the same.
  v1::EStopRequest estop;
  estop.set_reason("bob saw a hand in the cell");
  v1::EStopResponse stopped;
  ASSERT_TRUE(stub->EStop(context(kToken, "bob").get(), estop, &stopped).ok());
  const v1::RobotState halted = read_state(*stub);
  EXPECT_TRUE(halted.estop());
  EXPECT_EQ(halted.mode(), v1::ROBOT_MODE_ESTOPPED);
  EXPECT_EQ(halted.estop_reason(), "bob saw a hand in the cell");

  // Latched: motion is refused until reset, and stays refused over time.
  jog.set_expires_ns(core::monotonic_ns() + 2'000'000'000);
  grpc::Status status = stub->Jog(context().get(), jog, &jogged);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::FAILED_PRECONDITION);
  EXPECT_THAT(status.error_message(), HasSubstr("e-stop is engaged"));
  auto trajectory = trajectory_request("after-estop", q_of(halted), 0.02);
  trajectory.set_lease_id(lease.lease_id());
  v1::ExecuteTrajectoryResponse executed;
  status = stub->ExecuteTrajectory(context().get(), trajectory, &executed);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::FAILED_PRECONDITION);

  // Only the lease holder resets it.
  v1::ResetEStopRequest reset;
  v1::ResetEStopResponse was_reset;
  status = stub->ResetEStop(context(kToken, "bob").get(), reset, &was_reset);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::PERMISSION_DENIED);
  reset.set_lease_id(lease.lease_id());
  ASSERT_TRUE(stub->ResetEStop(context().get(), reset, &was_reset).ok());
  const v1::RobotState idle = read_state(*stub);
  EXPECT_FALSE(idle.estop());
  EXPECT_EQ(idle.mode(), v1::ROBOT_MODE_IDLE);
  EXPECT_TRUE(q_of(idle).isApprox(q_of(halted), 0.0));
}

TEST(RobotServer, ShutsDownCleanlyWithAStreamingClient) {
  auto server = start_server();
  auto stub = stub_for(*server);
  grpc::ClientContext c;
  v1::StreamStateRequest request;
  request.set_rate_hz(100);
  auto reader = stub->StreamState(&c, request);
  v1::RobotState state;
  ASSERT_TRUE(reader->Read(&state));
  server->shutdown();
  while (reader->Read(&state)) {
  }
  const grpc::Status status = reader->Finish();
  EXPECT_EQ(status.error_code(), grpc::StatusCode::UNAVAILABLE);
  EXPECT_THAT(status.error_message(), HasSubstr("shutting down"));
}

TEST(RobotServer, StartFailsWithAClearMessage) {
  RobotServerOptions options = server_options();
  options.token.clear();
  options.token_file = "/nonexistent/token";
  auto driver = sim::SimRobotDriver::create(telear::test::puma560());
  ASSERT_TRUE(driver);
  auto server = RobotServer::create(std::move(driver).value(), options);
  ASSERT_FALSE(server);
  EXPECT_THAT(server.error().message, HasSubstr("cannot read the token file '/nonexistent/token'"));
}

}  // namespace
}  // namespace telear::net::test
