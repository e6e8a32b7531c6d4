#include "telear/core/ik_redundant.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "telear/core/ik_numeric.hpp"
#include "telear/core/inverse_kinematics.hpp"
#include "telear/core/joint_limits.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/motion_command.hpp"
#include "telear/core/pose.hpp"
#include "test_arms.hpp"
#include "test_util/test_util.hpp"

namespace telear::core {
namespace {

using ::testing::HasSubstr;

void expect_reaches(const RobotModel& model, const Eigen::VectorXd& q, const Eigen::Isometry3d& T,
                    double tolerance) {
  const Vector6d e = pose_error_in_base(tool_pose(model, q), T);
  EXPECT_LT(e.head<3>().norm(), tolerance);
  EXPECT_LT(e.tail<3>().norm(), tolerance);
}

TEST(RedundantIk, RoundTripWithinLimitsAtRandomReachablePoses) {
  const RobotModel model = test_arms::panda_like();
  std::mt19937_64 rng(7);
  const Eigen::VectorXd ready = test_arms::panda_ready();
  RedundancyOptions rest;
  rest.preference = NullSpacePreference::kRest;
  rest.rest_q = ready;
  for (int k = 0; k < 300; ++k) {
    const Eigen::VectorXd q_true = test::random_configuration(model, rng);
    const Eigen::Isometry3d T = tool_pose(model, q_true);
    // From the ready pose (default preference: near it) and towards the rest pose.
    for (const RedundancyOptions& options : {RedundancyOptions{}, rest}) {
      auto s = solve_ik_nearest(model, T, ready, options);
      ASSERT_TRUE(s) << k << ": " << s.error().message;
      EXPECT_EQ(s->config, "redundant");
      EXPECT_TRUE(within_limits(model, s->q)) << s->q.transpose();
      expect_reaches(model, s->q, T, 1e-9);
    }
  }
}

TEST(RedundantIk, NullSpaceBringsTheSolutionCloserToThePreferenceThanPlainLm) {
  const RobotModel model = test_arms::panda_like();
  std::mt19937_64 rng(11);
  // The preference alone (no limit penalty): h is then half the squared distance.
  RedundancyOptions options;
  options.preference = NullSpacePreference::kRest;
  options.rest_q = test_arms::panda_ready();
  options.limit_weight = 0.0;
  NumericIkOptions precise;
  precise.position_tolerance_m = precise.orientation_tolerance_rad = 1e-9;
  NumericIkSolver lm(model, precise);
  int closer = 0;
  const int cases = 100;
  for (int k = 0; k < cases; ++k) {
    const Eigen::VectorXd q_true = test::random_configuration(model, rng);
    const Eigen::VectorXd seed = test::random_configuration(model, rng);
    const Eigen::Isometry3d T = tool_pose(model, q_true);
    const NumericIkResult plain = lm.solve(T, seed);
    ASSERT_TRUE(plain.success);
    const NullSpaceResult r = optimize_null_space(model, T, plain.q, options.rest_q, options);
    expect_reaches(model, r.q, T, 1e-9);
    EXPECT_TRUE(within_limits(model, r.q));
    EXPECT_LE(r.cost_after, r.cost_before);
    EXPECT_DOUBLE_EQ(r.cost_after, null_space_cost(model, r.q, options.rest_q, options));
    const double d_plain = (plain.q - options.rest_q).norm();
    const double d_null = (r.q - options.rest_q).norm();
    EXPECT_LE(d_null, d_plain + 1e-9) << k;
    if (d_null < d_plain - 1e-3) ++closer;
  }
  EXPECT_GE(closer, cases * 9 / 10);
}

TEST(RedundantIk, DefaultPreferenceStaysAtTheCurrentPoseAndIsDeterministic) {
  const RobotModel model = test_arms::panda_like();
  Eigen::VectorXd q(7);
  q << 0.3, -0.4, 0.5, -2.0, 0.4, 1.8, -0.3;
  const Eigen::Isometry3d T = tool_pose(model, q);
  auto s = solve_ik_nearest(model, T, q);
  ASSERT_TRUE(s);
  EXPECT_LT((s->q - q).cwiseAbs().maxCoeff(), 1e-6);
  // A pose elsewhere: the same answer twice, bit for bit.
  Eigen::Isometry3d T2 = T;
  T2.translation() += Eigen::Vector3d(0.1, -0.05, 0.08);
  auto a = solve_ik_nearest(model, T2, q);
  auto b = solve_ik_nearest(model, T2, q);
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->q, b->q);
}

// A 20 cm circle with a turn back and forth, in 200 steps of about 6 mm and up to 0.01 rad,
// each solved from the previous answer; returns the final configuration.
Eigen::VectorXd follow_circle(const RobotModel& model, const RedundancyOptions& options) {
  Eigen::VectorXd q = test_arms::panda_ready();
  const Eigen::Isometry3d T0 = tool_pose(model, q);
  for (int k = 1; k <= 200; ++k) {
    const double s = 2.0 * std::numbers::pi * k / 200.0;
    Eigen::Isometry3d T = T0;
    T.translation() += Eigen::Vector3d(0.1 * (std::cos(s) - 1.0), 0.1 * std::sin(s), 0.0);
    T.linear() = Eigen::AngleAxisd(0.3 * std::sin(s), Eigen::Vector3d::UnitZ()) * T0.linear();
    auto r = solve_ik_nearest(model, T, q, options);
    EXPECT_TRUE(r) << k << ": " << r.error().message;
    if (!r) return q;
    EXPECT_LT((r->q - q).cwiseAbs().maxCoeff(), 0.05) << "step " << k << " jumps";
    EXPECT_TRUE(within_limits(model, r->q));
    expect_reaches(model, r->q, T, 1e-9);
    q = r->q;
  }
  return q;
}

TEST(RedundantIk, SmallTargetMotionsGiveSmallJointMotions) {
  const RobotModel model = test_arms::panda_like();
  // Near the current pose: smooth, but, like any velocity-level scheme, not cyclic (the
  // arm may come back to the same pose in another configuration of the self-motion).
  follow_circle(model, RedundancyOptions{});
  // Near a rest pose: the answer is a function of the pose, so the loop closes.
  RedundancyOptions rest;
  rest.preference = NullSpacePreference::kRest;
  rest.rest_q = test_arms::panda_ready();
  const Eigen::VectorXd end = follow_circle(model, rest);
  EXPECT_LT((end - test_arms::panda_ready()).cwiseAbs().maxCoeff(), 1e-5);
}

TEST(RedundantIk, LimitPenaltyKeepsJointsAwayFromTheirLimits) {
  const RobotModel model = test_arms::panda_like();
  // Preferred pose with joint 3 close to its upper limit (2.8973), inside the penalty's band
  // (0.1 of its range, 0.58 rad): the penalty moves the arm along its self-motion (the elbow
  // swivel, which turns joint 3) out of the band, at the same pose.
  Eigen::VectorXd q(7);
  q << 0.1, 0.3, 2.8, -1.5, 0.1, 1.0, 0.2;
  const Eigen::Isometry3d T = tool_pose(model, q);
  RedundancyOptions without;
  without.limit_weight = 0.0;
  const RedundancyOptions with;  // the default weight, 1
  const NullSpaceResult a = optimize_null_space(model, T, q, q, without);
  const NullSpaceResult b = optimize_null_space(model, T, q, q, with);
  expect_reaches(model, b.q, T, 1e-9);
  EXPECT_TRUE(within_limits(model, b.q));
  EXPECT_LT((a.q - q).norm(), 1e-9);  // no penalty: already at the preferred pose
  const double upper3 = model.upper_limits()[2];
  EXPECT_GT(upper3 - b.q[2], upper3 - q[2] + 0.01) << b.q.transpose();
  EXPECT_LT(b.cost_after, b.cost_before);
}

TEST(RedundantIk, OptionsAreValidatedNamingTheField) {
  const RobotModel model = test_arms::panda_like();
  const Eigen::VectorXd q = test_arms::panda_ready();
  const Eigen::Isometry3d T = tool_pose(model, q);
  RedundancyOptions o;
  o.preference = NullSpacePreference::kRest;
  o.rest_q = Eigen::VectorXd::Zero(6);
  auto r = solve_ik_nearest(model, T, q, o);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().message,
            "RedundancyOptions::rest_q has 6 values, expected 7 (one per joint of panda_like)");
  o.rest_q = Eigen::VectorXd::Zero(7);  // joint 4's range excludes 0
  EXPECT_THAT(check_redundancy_options(model, o).error().message,
              HasSubstr("RedundancyOptions::rest_q[3] = 0 is not within the limits of joint 4"));
  o = {};
  o.limit_margin = 0.0;
  EXPECT_THAT(check_redundancy_options(model, o).error().message,
              HasSubstr("RedundancyOptions::limit_margin must be in (0, 0.5], got 0"));
  o = {};
  o.limit_weight = -1.0;
  EXPECT_THAT(check_redundancy_options(model, o).error().message,
              HasSubstr("RedundancyOptions::limit_weight"));
  o = {};
  o.max_iterations = 0;
  EXPECT_THAT(check_redundancy_options(model, o).error().message,
              HasSubstr("RedundancyOptions::max_iterations must be positive, got 0"));
  o = {};
  o.pose_tolerance = std::nan("");
  EXPECT_THAT(check_redundancy_options(model, o).error().message,
              HasSubstr("RedundancyOptions::pose_tolerance must be positive and finite"));
  // Through a motion command: rejected as invalid input, q unchanged.
  MotionOptions motion;
  motion.redundancy.max_iterations = -3;
  const MotionOutcome out = apply_motion(
      model, q, CartesianIncrement{MotionFrame::kBase, {0.01, 0, 0}, {0, 0, 0}}, motion);
  EXPECT_FALSE(out.accepted);
  EXPECT_EQ(out.rejection.kind, RejectionKind::kInvalidInput);
  EXPECT_THAT(out.rejection.message, HasSubstr("RedundancyOptions::max_iterations"));
  EXPECT_EQ(out.q, q);
}

TEST(RedundantIk, CartesianJogInBaseWristAndToolFrames) {
  const RobotModel model = test_arms::panda_like();
  for (MotionFrame frame : {MotionFrame::kBase, MotionFrame::kWrist, MotionFrame::kTool}) {
    Eigen::VectorXd q = test_arms::panda_ready();
    const CartesianIncrement step{frame, {0.004, -0.003, 0.005}, {0.01, -0.02, 0.015}};
    for (int k = 0; k < 30; ++k) {
      KinematicsData data(model);
      forward_kinematics(model, data, q);
      const Eigen::Isometry3d expected = incremented_tool_pose(model, data, step);
      const MotionOutcome out = apply_motion(model, q, step);
      ASSERT_TRUE(out.accepted) << to_string(frame) << " step " << k << ": "
                                << out.rejection.message;
      EXPECT_EQ(out.ik_config, "redundant");
      EXPECT_TRUE(within_limits(model, out.q));
      expect_reaches(model, out.q, expected, 1e-9);
      EXPECT_LT((out.q - q).cwiseAbs().maxCoeff(), 0.1) << to_string(frame) << " step " << k;
      q = out.q;
    }
  }
}

TEST(RedundantIk, JogTowardsALimitStopsAtItWithoutLeavingIt) {
  const RobotModel model = test_arms::panda_like();
  Eigen::VectorXd q = test_arms::panda_ready();
  // Straight up in the base frame until the arm cannot follow: every accepted step within the
  // limits, and the first rejection says why.
  const CartesianIncrement up{MotionFrame::kBase, {0.0, 0.0, 0.02}, {0, 0, 0}};
  bool rejected = false;
  for (int k = 0; k < 100 && !rejected; ++k) {
    const MotionOutcome out = apply_motion(model, q, up);
    if (!out.accepted) {
      rejected = true;
      EXPECT_EQ(out.q, q);
      EXPECT_EQ(out.rejection.kind, RejectionKind::kUnreachable);
      break;
    }
    EXPECT_TRUE(within_limits(model, out.q));
    q = out.q;
  }
  EXPECT_TRUE(rejected) << "2 m up is out of reach";
}

}  // namespace
}  // namespace telear::core
