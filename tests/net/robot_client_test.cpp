// RobotClient against a real robot server on loopback: the state stream, the lease with its
// heartbeat, commands with the server's reasons, reconnecting after a server restart.

#include "telear/net/robot_client.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

#include "robot_test_support.hpp"

namespace telear::net::test {
namespace {

using ::testing::HasSubstr;

RobotClientOptions client_options(const RobotServer& server, const std::string& name,
                                  const std::string& token = kToken) {
  RobotClientOptions options;
  options.address = server.address();
  options.token = token;
  options.client_name = name;
  options.state_rate_hz = 250;
  options.reconnect_initial_backoff_s = 0.02;
  options.reconnect_max_backoff_s = 0.2;
  return options;
}

// Waits for a state that satisfies `done`; fails the test after timeout_s.
template <typename Done>
RobotStateSample wait_for(const RobotClient& client, Done done, double timeout_s = 5.0) {
  const std::int64_t deadline = core::monotonic_ns() + core::s_to_ns(timeout_s);
  std::uint64_t after = 0;
  while (core::monotonic_ns() < deadline) {
    if (auto sample = client.wait_state(after, 0.1)) {
      if (done(*sample)) return *sample;
      after = sample->sequence;
    }
  }
  ADD_FAILURE() << "no such state within " << timeout_s << " s";
  return {};
}

TEST(RobotClient, ReadsInfoAndStateAndTheClockOffset) {
  auto server = start_server();
  RobotClient client(client_options(*server, "observer", ""));
  auto info = client.get_info();
  ASSERT_TRUE(info) << info.error().message;
  EXPECT_EQ(info->model_name, "puma560");
  EXPECT_EQ(info->joints.size(), 6u);
  EXPECT_DOUBLE_EQ(info->heartbeat_period_s, 0.25);
  client.start();
  const RobotStateSample sample = wait_for(client, [](const auto&) { return true; });
  EXPECT_EQ(sample.state.q.size(), 6);
  EXPECT_GE(sample.receive_ns, sample.capture_ns);  // loopback: one clock
  EXPECT_TRUE(client.connected());
  auto rtt = client.ping();
  ASSERT_TRUE(rtt) << rtt.error().message;
  ASSERT_TRUE(client.clock_offset().has_value());
  // Loopback: the same clock, so the estimate is within its own error bound of zero.
  EXPECT_LE(std::abs(client.clock_offset()->offset_ns), client.clock_offset()->error_bound_ns);
  // An observer cannot command.
  const Status refused = client.acquire_lease();
  ASSERT_FALSE(refused);
  EXPECT_THAT(refused.error().message, HasSubstr("acquire lease: no token"));
}

TEST(RobotClient, HoldsTheLeaseWithItsHeartbeatAndExecutesATrajectory) {
  auto server = start_server();
  RobotClient alice(client_options(*server, "alice"));
  RobotClient bob(client_options(*server, "bob"));
  alice.start();
  ASSERT_TRUE(alice.acquire_lease(0.1));  // 100 ms: the heartbeat renews every 33 ms
  const Status refused = bob.acquire_lease();
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().message,
            "acquire lease: the lease is held by 'alice'; wait until it is released or lapses "
            "(it is renewed every 100 ms)");

  const RobotStateSample start =
      wait_for(alice, [](const auto& s) { return s.lease_holder == "alice"; });
  const Eigen::VectorXd q0 = start.state.q;
  auto trajectory = core::Trajectory::create(*telear::test::puma560(),
                                             {{q0}, {Eigen::VectorXd(q0.array() + 0.05)}});
  ASSERT_TRUE(trajectory);
  auto sampled = trajectory->sampled(50.0);
  ASSERT_TRUE(sampled);
  auto ack = alice.execute("reach-1", *sampled);
  ASSERT_TRUE(ack) << ack.error().message;
  EXPECT_FALSE(ack->duplicate);
  EXPECT_GT(alice.command_bytes_sent(), 0u);

  // Several heartbeat periods pass while it runs: the lease holds.
  const RobotStateSample done =
      wait_for(alice, [](const auto& s) { return s.last_trajectory_id == "reach-1"; });
  EXPECT_EQ(done.last_trajectory_status, core::TrajectoryStatus::kCompleted);
  EXPECT_TRUE(alice.lease_held()) << alice.lease_error();
  EXPECT_TRUE(done.state.q.isApprox(Eigen::VectorXd(q0.array() + 0.05), 1e-9));

  // A rejected command carries the server's reason, prefixed by the command.
  auto again = alice.execute("reach-2", *sampled);  // starts 0.05 rad away from the arm now
  ASSERT_FALSE(again);
  EXPECT_THAT(again.error().message,
              HasSubstr("execute: trajectory 'reach-2' rejected: it starts 0.050 rad"));
  ASSERT_TRUE(alice.release_lease());
  EXPECT_FALSE(alice.lease_held());
  ASSERT_TRUE(bob.acquire_lease());
}

TEST(RobotClient, ReportsALostLease) {
  auto server = start_server();
  RobotClient alice(client_options(*server, "alice"));
  ASSERT_TRUE(alice.acquire_lease(0.1));
  // The server goes away: renewals fail, and a heartbeat period after the last one that
  // succeeded the client reports the lease lost (the server, had it lived, stopped the arm).
  server->shutdown();
  const std::int64_t deadline = core::monotonic_ns() + 3'000'000'000;
  while (alice.lease_held() && core::monotonic_ns() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_FALSE(alice.lease_held());
  EXPECT_THAT(alice.lease_error(), HasSubstr("lease lost: renew lease: robot server at"));
}

TEST(RobotClient, ReconnectsAfterAServerRestartOnTheSamePort) {
  auto server = start_server();
  const std::string address = server->address();
  RobotClient client(client_options(*server, "observer", ""));
  client.start();
  const RobotStateSample first = wait_for(client, [](const auto&) { return true; });
  server->shutdown();
  server.reset();
  server = start_server(server_options(address));
  ASSERT_NE(server, nullptr);
  // A state captured by the new server (its stream restarted): newer than anything before.
  const RobotStateSample later = wait_for(client, [&](const RobotStateSample& s) {
    return s.capture_ns > first.capture_ns && client.reconnect_stats().successes >= 1;
  });
  const ReconnectStats stats = client.reconnect_stats();
  EXPECT_GE(stats.successes, 1u);
  EXPECT_GE(stats.attempts, stats.successes);
  // The stream the shutdown ended says why, naming the server.
  EXPECT_THAT(stats.last_error, HasSubstr("stream: "));
  EXPECT_GT(later.sequence, first.sequence);
  client.stop();
}

TEST(RobotClient, JogsAndStopsWithTheServersReasons) {
  auto server = start_server();
  RobotClient alice(client_options(*server, "alice"));
  alice.start();
  ASSERT_TRUE(alice.acquire_lease());
  auto jog = alice.jog(core::JointIncrement{0, 0.05}, 1.0);
  ASSERT_TRUE(jog) << jog.error().message;
  ASSERT_EQ(jog->target_q.size(), 6);
  auto expired = alice.jog(core::JointIncrement{0, 0.05}, -0.05);
  ASSERT_FALSE(expired);
  EXPECT_THAT(expired.error().message, HasSubstr("jog: jog ignored: it expired"));
  auto too_fast = alice.jog_velocity(Eigen::VectorXd::Constant(6, 100.0));
  ASSERT_FALSE(too_fast);
  EXPECT_THAT(too_fast.error().message, HasSubstr("exceeds its max velocity"));
  ASSERT_TRUE(alice.estop("test"));
  const RobotStateSample halted = wait_for(alice, [](const auto& s) { return s.state.estop; });
  EXPECT_EQ(halted.state.mode, core::RobotMode::kEStopped);
  ASSERT_TRUE(alice.reset_estop());
  ASSERT_TRUE(alice.set_gripper(0.5));
  ASSERT_TRUE(alice.cancel());
}

// The simulated driver, recording what the server shows it of the operator's rehearsal.
class GhostRecordingDriver final : public core::RobotDriver {
 public:
  explicit GhostRecordingDriver(std::unique_ptr<core::RobotDriver> inner)
      : inner_(std::move(inner)) {}
  const core::RobotModelPtr& model() const override { return inner_->model(); }
  std::string name() const override { return inner_->name(); }
  std::string urdf() const override { return inner_->urdf(); }
  double start_tolerance() const override { return inner_->start_tolerance(); }
  core::DriverSnapshot snapshot() const override { return inner_->snapshot(); }
  std::optional<core::TrajectoryRecord> trajectory_record(const std::string& id) const override {
    return inner_->trajectory_record(id);
  }
  Result<core::MotionOutcome> jog(const core::MotionCommand& c, std::int64_t e) override {
    return inner_->jog(c, e);
  }
  Status jog_velocity(const Eigen::VectorXd& qd, std::int64_t e) override {
    return inner_->jog_velocity(qd, e);
  }
  Result<core::DriverAcceptance> execute(const std::string& id,
                                         const core::TimedWaypoints& w) override {
    return inner_->execute(id, w);
  }
  void stop(const std::string& reason) override { inner_->stop(reason); }
  Status set_gripper(double opening) override { return inner_->set_gripper(opening); }
  void estop(const std::string& reason) override { inner_->estop(reason); }
  Status reset_estop() override { return inner_->reset_estop(); }
  void show_ghost(const Eigen::VectorXd& q, double gripper) override {
    std::lock_guard lock(mutex_);
    ghosts_.emplace_back(q, gripper);
  }
  std::vector<std::pair<Eigen::VectorXd, double>> ghosts() const {
    std::lock_guard lock(mutex_);
    return ghosts_;
  }

 private:
  std::unique_ptr<core::RobotDriver> inner_;
  mutable std::mutex mutex_;
  std::vector<std::pair<Eigen::VectorXd, double>> ghosts_;
};

struct GhostServer {
  GhostRecordingDriver* driver = nullptr;
  std::unique_ptr<RobotServer> server;
};

GhostServer start_ghost_server() {
  auto sim = sim::SimRobotDriver::create(telear::test::puma560());
  EXPECT_TRUE(sim) << sim.error().message;
  auto driver = std::make_unique<GhostRecordingDriver>(std::move(sim).value());
  GhostServer started{driver.get(), nullptr};
  auto server = RobotServer::create(std::move(driver), server_options());
  EXPECT_TRUE(server) << server.error().message;
  started.server = std::move(server).value();
  return started;
}

}  // namespace
}  // namespace telear::net::test

namespace telear::net::test {
namespace {

TEST(RobotClient, TheGhostRidesOnTheLeaseHeartbeat) {
  GhostServer ghost = start_ghost_server();
  RobotClient client(client_options(*ghost.server, "alice"));
  client.start();
  Eigen::VectorXd q(6);
  q << 0.1, 0.2, -0.3, 0.0, 0.4, 0.0;
  client.set_ghost(q, 0.5);  // no lease yet: nothing is sent
  std::this_thread::sleep_for(std::chrono::milliseconds(150));
  EXPECT_TRUE(ghost.driver->ghosts().empty());
  ASSERT_TRUE(client.acquire_lease(0.1));
  auto seen = [&](std::size_t n) {
    const std::int64_t deadline = core::monotonic_ns() + 2'000'000'000;
    while (ghost.driver->ghosts().size() < n && core::monotonic_ns() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return ghost.driver->ghosts();
  };
  auto ghosts = seen(1);
  ASSERT_EQ(ghosts.size(), 1u);
  EXPECT_EQ(ghosts[0].first, q);
  EXPECT_EQ(ghosts[0].second, 0.5);
  // Unchanged: not sent again, though the heartbeat goes on (every 33 ms).
  client.set_ghost(q, 0.5);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_EQ(ghost.driver->ghosts().size(), 1u);
  // A change rides on the next renewal; the gripper alone is a change.
  client.set_ghost(q, 1.0);
  ghosts = seen(2);
  ASSERT_EQ(ghosts.size(), 2u);
  EXPECT_EQ(ghosts[1].second, 1.0);
  EXPECT_TRUE(client.lease_held()) << client.lease_error();
}

// Issue 22: observers (a recorder, another operator) see the holder's ghost in the state
// stream, stamped on the server clock, until the lease ends.
TEST(RobotClient, AnObserverSeesTheHoldersGhostInTheStateStream) {
  GhostServer ghost = start_ghost_server();
  RobotClient holder(client_options(*ghost.server, "alice"));
  RobotClient observer(client_options(*ghost.server, "recorder"));
  holder.start();
  observer.start();
  auto state_with_ghost = [&](bool want) {
    const std::int64_t deadline = core::monotonic_ns() + 2'000'000'000;
    std::optional<RobotStateSample> s;
    while (core::monotonic_ns() < deadline) {
      s = observer.latest_state();
      if (s && (s->ghost_q.size() > 0) == want) return s;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return s;
  };
  auto before = state_with_ghost(false);
  ASSERT_TRUE(before);
  EXPECT_EQ(before->ghost_q.size(), 0) << "no lease: no ghost";
  Eigen::VectorXd q(6);
  q << 0.1, 0.2, -0.3, 0.0, 0.4, 0.0;
  holder.set_ghost(q, 0.25);
  ASSERT_TRUE(holder.acquire_lease(0.1));
  const std::int64_t sent_after = core::monotonic_ns();
  auto seen = state_with_ghost(true);
  ASSERT_TRUE(seen && seen->ghost_q.size() == 6) << "the ghost never reached the stream";
  EXPECT_EQ(seen->ghost_q, q);
  EXPECT_EQ(seen->ghost_gripper, 0.25);
  EXPECT_GE(seen->ghost_ns, sent_after - 1'000'000'000);  // loopback: one clock
  EXPECT_LE(seen->ghost_ns, seen->capture_ns);
  ASSERT_TRUE(holder.release_lease());
  auto after = state_with_ghost(false);
  ASSERT_TRUE(after);
  EXPECT_EQ(after->ghost_q.size(), 0) << "the lease ended: the ghost is no longer streamed";
}

TEST(RobotServer, RefusesAnInvalidGhostOnARenewal) {
  GhostServer ghost = start_ghost_server();
  auto stub = stub_for(*ghost.server);
  const v1::Lease lease = acquire(*stub);
  auto renew = [&](std::vector<double> q, double gripper) {
    v1::RenewLeaseRequest request;
    request.set_lease_id(lease.lease_id());
    request.mutable_ghost_q()->Assign(q.begin(), q.end());
    request.set_ghost_gripper(gripper);
    v1::Lease response;
    return stub->RenewLease(context().get(), request, &response);
  };
  grpc::Status s = renew({0, 0, 0, 0, 0}, 0.0);
  EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(s.error_message(), "renew lease: ghost rejected: 5 joint values for a 6-joint arm");
  s = renew({0, 0, std::nan(""), 0, 0, 0}, 0.0);
  EXPECT_EQ(s.error_message(), "renew lease: ghost rejected: a joint value is not a finite number");
  s = renew({0, 2.5, 0, 0, 0, 0}, 0.0);
  EXPECT_THAT(s.error_message(), HasSubstr("ghost rejected: joint 2 (shoulder)"));
  EXPECT_THAT(s.error_message(), HasSubstr("upper limit"));
  s = renew({0, 0, 0, 0, 0, 0}, 1.5);
  EXPECT_EQ(s.error_message(),
            "renew lease: ghost rejected: gripper opening 1.5 is outside [0, 1]");
  EXPECT_TRUE(ghost.driver->ghosts().empty());
  s = renew({0, 0, 0, 0, 0, 0}, 1.0);
  EXPECT_TRUE(s.ok()) << s.error_message();
  ASSERT_EQ(ghost.driver->ghosts().size(), 1u);
}

}  // namespace
}  // namespace telear::net::test
