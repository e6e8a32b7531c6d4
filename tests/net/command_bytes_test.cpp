// What a motion costs on the wire: the plan is exactly the request RobotClient sends, the jog
// stream one joint-target jog per sample of the same span.

#include "telear/net/command_bytes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "robot_test_support.hpp"
#include "telear/core/plan_hash.hpp"
#include "telear/net/robot_client.hpp"

namespace telear::net::test {
namespace {

// A core-timed motion from `q0` by `delta` on every joint, at most `velocity_scale` of the
// limits, sampled at rate_hz.
core::TimedWaypoints motion(const Eigen::VectorXd& q0, double delta, double velocity_scale,
                            double rate_hz) {
  core::TrajectoryOptions options;
  options.velocity_scale = velocity_scale;
  options.acceleration_scale = velocity_scale;
  auto trajectory = core::Trajectory::create(
      *telear::test::puma560(), {{q0}, {Eigen::VectorXd(q0.array() + delta)}}, options);
  EXPECT_TRUE(trajectory) << trajectory.error().message;
  auto sampled = trajectory->sampled(rate_hz);
  EXPECT_TRUE(sampled) << sampled.error().message;
  return *sampled;
}

TEST(CommandBytes, ThePlanIsTheRequestTheClientSends) {
  auto server = start_server();
  RobotClientOptions options;
  options.address = server->address();
  options.token = kToken;
  options.client_name = "alice";
  RobotClient client(options);
  client.start();
  ASSERT_TRUE(client.acquire_lease(5.0));
  const std::uint64_t before = client.command_bytes_sent();
  const Eigen::VectorXd q0 = [&] {
    auto sample = client.wait_state(0, 2.0);
    EXPECT_TRUE(sample.has_value());
    return sample ? sample->state.q : Eigen::VectorXd::Zero(6).eval();
  }();
  const core::TimedWaypoints plan = motion(q0, 0.02, 1.0, 50.0);
  auto ack = client.execute("reach-1", plan);
  ASSERT_TRUE(ack) << ack.error().message;
  const std::uint64_t sent = client.command_bytes_sent() - before;
  // The server's lease ids are 32 characters; only their length matters for the size.
  const CommandBytes bytes = compare_command_bytes(plan, 100.0, std::string(32, '0'), "reach-1");
  EXPECT_EQ(bytes.plan_bytes, sent);
}

TEST(CommandBytes, ThePlanMessageIsTheRequestExecutePlanSends) {
  auto server = start_server();
  RobotClientOptions options;
  options.address = server->address();
  options.token = kToken;
  options.client_name = "alice";
  RobotClient client(options);
  client.start();
  ASSERT_TRUE(client.acquire_lease(5.0));
  auto sample = client.wait_state(0, 2.0);
  ASSERT_TRUE(sample.has_value());
  const Eigen::VectorXd q0 = sample->state.q;
  Eigen::VectorXd q1 = q0, q2 = q0;
  q1[0] += 0.05;
  q2[0] += 0.05;
  q2[1] += 0.05;
  auto trajectory = core::Trajectory::create(*telear::test::puma560(),
                                             {{q0}, {q1, 0.0, std::nullopt, true}, {q2}});
  ASSERT_TRUE(trajectory) << trajectory.error().message;
  const std::uint64_t before = client.command_bytes_sent();
  auto ack = client.execute_plan("reach-plan", *trajectory);
  ASSERT_TRUE(ack) << ack.error().message;
  EXPECT_EQ(ack->plan_id, "reach-plan");
  EXPECT_FALSE(ack->duplicate);
  EXPECT_EQ(ack->plan_hash, *core::plan_hash(*trajectory));
  EXPECT_EQ(ack->duration_s, trajectory->duration());
  const auto bytes = plan_message_bytes(*trajectory, std::string(32, '0'), "reach-plan");
  ASSERT_TRUE(bytes) << bytes.error().message;
  EXPECT_EQ(*bytes, client.command_bytes_sent() - before);
  // Three waypoints: a few hundred bytes, against a kilobyte and more for the samples.
  const CommandBytes samples =
      compare_command_bytes(*trajectory->sampled(100.0), 100.0, std::string(32, '0'), "p");
  EXPECT_LT(*bytes, samples.plan_bytes);
  EXPECT_LT(*bytes, samples.jog_stream_bytes);
}

TEST(CommandBytes, JogsOncePerSampleOfTheSpanAndCostsMoreThanThePlan) {
  const Eigen::VectorXd q0 = Eigen::VectorXd::Zero(6);
  // Slow enough to take several seconds.
  const core::TimedWaypoints plan = motion(q0, 0.5, 0.1, 100.0);
  const double span = plan.times.back() - plan.times.front();
  ASSERT_GT(span, 3.0);
  const CommandBytes bytes = compare_command_bytes(plan, 100.0, std::string(32, '0'), "plan-1");
  EXPECT_EQ(bytes.jog_messages, static_cast<int>(std::floor(span * 100.0 + 1e-9)) + 1);
  EXPECT_GT(bytes.plan_bytes, 0u);
  EXPECT_GT(bytes.jog_stream_bytes, bytes.plan_bytes);
  // Every jog carries the lease id, an expiry and six doubles: more than 32 + 48 bytes.
  EXPECT_GT(bytes.jog_stream_bytes, static_cast<std::uint64_t>(bytes.jog_messages) * 80u);

  // At 10 Hz the stream has a tenth of the messages (same span).
  const CommandBytes slow = compare_command_bytes(plan, 10.0, std::string(32, '0'), "plan-1");
  EXPECT_EQ(slow.jog_messages, static_cast<int>(std::floor(span * 10.0 + 1e-9)) + 1);
  EXPECT_EQ(slow.plan_bytes, bytes.plan_bytes);
}

TEST(CommandBytes, ASingleSampleIsOneJog) {
  core::TimedWaypoints plan;
  plan.times = {0.0};
  plan.q = {Eigen::VectorXd::Zero(6)};
  const CommandBytes bytes = compare_command_bytes(plan, 100.0, "lease", "id");
  EXPECT_EQ(bytes.jog_messages, 1);
  EXPECT_GT(bytes.jog_stream_bytes, 0u);
}

}  // namespace
}  // namespace telear::net::test
