#include "telear/session/execution_monitor.hpp"

#include <gtest/gtest.h>

#include <iostream>

#include "test_util/test_util.hpp"

namespace telear::session {
namespace {

class ExecutionMonitorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    model_ = test::puma560();
    Eigen::VectorXd a = Eigen::VectorXd::Zero(6), b = Eigen::VectorXd::Zero(6);
    b[1] = 0.6;
    b[2] = -0.4;
    auto t = core::Trajectory::create(*model_, {{a}, {b, 2.0}});
    ASSERT_TRUE(t.ok());
    trajectory_ = std::make_unique<core::Trajectory>(*t);
  }
  core::RobotModelPtr model_;
  std::unique_ptr<core::Trajectory> trajectory_;
};

TEST_F(ExecutionMonitorTest, PerfectTrackingCompletes) {
  ExecutionMonitor monitor(model_, *trajectory_, 100.0);
  const double d = trajectory_->duration();
  for (int k = 0; k <= 50; ++k) {
    const double t = d * k / 50.0;
    const TrackingStatus& s = monitor.update(100.0 + t, trajectory_->sample(t).q);
    EXPECT_FALSE(s.cancel);
    EXPECT_NEAR(s.progress, t / d, 1e-12);
    EXPECT_LT(s.max_abs_error, 1e-12);
  }
  EXPECT_TRUE(monitor.complete());
  EXPECT_EQ(monitor.status().samples, 51);
  EXPECT_LT(monitor.status().max_error_so_far, 1e-12);
  // Samples before the start compare against the start.
  ExecutionMonitor early(model_, *trajectory_, 100.0);
  EXPECT_EQ(early.update(99.0, trajectory_->sample(0).q).plan_time, 0.0);
  EXPECT_FALSE(early.complete());
}

TEST_F(ExecutionMonitorTest, CancelsWhenAJointDeviatesSayingWhereAndByHowMuch) {
  ExecutionMonitor monitor(model_, *trajectory_, 10.0, {.tolerance = 0.05});
  // The shoulder (joint 2) lags more and more, as if a fault held it back.
  TrackingStatus last;
  for (int k = 0; k <= 100 && !monitor.cancelled(); ++k) {
    const double t = 0.01 * k;
    Eigen::VectorXd q = trajectory_->sample(t).q;
    q[1] -= 0.06 * t;  // 0.06 rad per second of lag
    last = monitor.update(10.0 + t, q);
  }
  ASSERT_TRUE(last.cancel);
  std::cout << last.cancel_message << "\n";
  EXPECT_EQ(last.worst_joint, 1);
  EXPECT_NEAR(last.plan_time, 0.84, 1e-9);  // first sample beyond 0.05 rad
  EXPECT_NEAR(last.error[1], -0.0504, 1e-9);
  EXPECT_EQ(last.cancel_message.rfind("execution monitor: at 0.840 s of 2.000 s into the plan, "
                                      "joint 2 (shoulder) is 0.050 rad (2.9 deg) from the plan "
                                      "(real ",
                                      0),
            0u)
      << last.cancel_message;
  EXPECT_NE(last.cancel_message.find("beyond the tolerance of 0.050 rad (2.9 deg); cancelling"),
            std::string::npos)
      << last.cancel_message;
  // Latched: a good sample afterwards keeps the decision and the message.
  const std::string message = last.cancel_message;
  const TrackingStatus& after = monitor.update(11.0, trajectory_->sample(1.0).q);
  EXPECT_TRUE(after.cancel);
  EXPECT_EQ(after.cancel_message, message);
  EXPECT_FALSE(after.complete);
  EXPECT_NEAR(monitor.status().max_error_so_far, 0.0504, 1e-9);
  EXPECT_EQ(monitor.status().max_error_joint, 1);
}

TEST_F(ExecutionMonitorTest, PlanTimeFromTheRobotAndInvalidSamples) {
  ExecutionMonitor monitor(model_, *trajectory_, 0.0);
  const TrackingStatus& s = monitor.update_at_plan_time(1.0, trajectory_->sample(1.0).q);
  EXPECT_FALSE(s.cancel);
  EXPECT_DOUBLE_EQ(s.progress, 0.5);
  Eigen::VectorXd bad = trajectory_->sample(1.0).q;
  bad[4] = std::nan("");
  const TrackingStatus& invalid = monitor.update_at_plan_time(1.1, bad);
  ASSERT_TRUE(invalid.cancel);
  EXPECT_EQ(
      invalid.cancel_message.rfind("execution monitor: the robot reported an invalid state (", 0),
      0u)
      << invalid.cancel_message;
}

}  // namespace
}  // namespace telear::session
