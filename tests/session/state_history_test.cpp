// The reported states by capture time (issue 23): the arm at a frame's capture, interpolated
// between reports; the nearest report and "moving near t" the registration check uses.

#include "telear/session/state_history.hpp"

#include <gtest/gtest.h>

#include "test_util/test_util.hpp"

namespace telear::session {
namespace {

// A joint-space motion linear in time: q(t) = q0 + v t.
Eigen::VectorXd linear_q(double t) {
  return test::q6(0.1, -0.4, 0.5, 0, 0.3, 0) + t * test::q6(0.5, -0.2, 0.1, 0.05, 0, -0.3);
}

TEST(StateHistory, TheArmBetweenTwoReportsIsInterpolatedExactlyForALinearMotion) {
  StateHistory history;
  EXPECT_FALSE(history.at(0.0, 1.0));
  EXPECT_FALSE(history.nearest(0.0));
  for (int k = 0; k <= 100; ++k) history.add(k * 0.01, linear_q(k * 0.01), k < 50 ? 1.0 : 0.0);
  for (const double t : {0.0, 0.003, 0.255, 0.499, 0.5051, 0.9999, 1.0}) {
    const auto arm = history.at(t);
    ASSERT_TRUE(arm) << t;
    EXPECT_LT((arm->q - linear_q(t)).cwiseAbs().maxCoeff(), 1e-12) << t;
  }
  // The gripper moves in steps: the nearer report's.
  EXPECT_EQ(history.at(0.493)->gripper, 1.0);
  EXPECT_EQ(history.at(0.497)->gripper, 0.0);
  // Outside the reports: only within the tolerance, as the nearest one.
  EXPECT_FALSE(history.at(1.03, 0.02));
  ASSERT_TRUE(history.at(1.03, 0.05));
  EXPECT_EQ(history.at(1.03, 0.05)->q, linear_q(1.0));
  EXPECT_FALSE(history.at(-0.01));
  EXPECT_EQ(history.at(-0.01, 0.01)->q, linear_q(0.0));
}

TEST(StateHistory, KeepsItsSpanIgnoresOldReportsAndRefusesMixedSizes) {
  StateHistory history(0.5);
  for (int k = 0; k <= 100; ++k) history.add(k * 0.01, linear_q(k * 0.01), 1.0);
  EXPECT_EQ(history.size(), 51u);  // 0.50 .. 1.00
  EXPECT_FALSE(history.at(0.45, 0.01));
  history.add(0.7, linear_q(0.0), 1.0);  // older than the newest: ignored
  EXPECT_EQ(history.size(), 51u);
  EXPECT_EQ(history.nearest(0.7)->q, linear_q(70 * 0.01));
  history.add(1.1, test::q6(0, 0, 0, 0, 0, 0).head(5), 1.0);  // another arm's size
  EXPECT_FALSE(history.at(1.05));
  EXPECT_EQ(history.at(1.1)->q.size(), 5);
}

TEST(StateHistory, TheArmMovingNearATimeIsAReportAwayFromTheGivenPose) {
  StateHistory history;
  for (int k = 0; k <= 10; ++k) history.add(k * 0.01, linear_q(0.0), 1.0);  // at rest
  for (int k = 11; k <= 20; ++k) history.add(k * 0.01, linear_q(k * 0.01), 1.0);
  EXPECT_FALSE(history.moving_near(0.03, linear_q(0.0), 0.05, 1e-3));
  EXPECT_TRUE(history.moving_near(0.09, linear_q(0.0), 0.05, 1e-3));
  EXPECT_FALSE(history.moving_near(0.09, linear_q(0.0), 0.05, 0.5));
}

}  // namespace
}  // namespace telear::session
