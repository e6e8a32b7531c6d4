// RobotClient against a real robot server on loopback: the state stream, the lease with its
// heartbeat, commands with the server's reasons, reconnecting after a server restart.

#include "telear/net/robot_client.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <thread>

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

}  // namespace
}  // namespace telear::net::test
