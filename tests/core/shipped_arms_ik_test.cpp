// IK on the arms telear ships (data/robots: puma560, ur6, arm7), loaded the way every
// command loads them (load_robot_description by name), not built in code: round trips of
// solve_ik_nearest for every arm, and for the 7-joint arm its joint limits and the null-space
// preference (near the current pose by default, near a rest pose with kRest).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include "telear/core/inverse_kinematics.hpp"
#include "telear/core/joint_limits.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/motion_command.hpp"
#include "telear/core/pose.hpp"
#include "telear/core/robot_description.hpp"
#include "test_util/test_util.hpp"

namespace telear::core {
namespace {

RobotModelPtr shipped(const std::string& name) {
  auto d = load_robot_description({name, "", {}});
  EXPECT_TRUE(d) << d.error().message;
  return d ? d->model : nullptr;
}

double pose_error(const RobotModel& model, const Eigen::VectorXd& q, const Eigen::Isometry3d& T) {
  const Vector6d e = pose_error_in_base(tool_pose(model, q), T);
  return std::max(e.head<3>().norm(), e.tail<3>().norm());
}

// FK(IK(T)) = T within the limits at random reachable poses, from a random current pose,
// with the method each arm should get: its closed form (a PUMA or UR label) or, for the
// 7-joint arm, the null-space search.
TEST(ShippedArmsIk, RoundTripsForEveryArm) {
  struct Arm {
    const char* name;
    int dof;
    const char* method;  // "closed form" or "redundant"
    double tolerance;    // m and rad
  };
  for (const Arm& arm : {Arm{"puma560", 6, "closed form", 1e-10},
                         Arm{"ur6", 6, "closed form", 1e-10}, Arm{"arm7", 7, "redundant", 1e-9}}) {
    const RobotModelPtr model = shipped(arm.name);
    ASSERT_TRUE(model);
    ASSERT_EQ(model->dof(), arm.dof) << arm.name;
    std::mt19937_64 rng(21);
    for (int k = 0; k < 100; ++k) {
      const Eigen::VectorXd q_true = test::random_configuration(*model, rng);
      const Eigen::VectorXd q_current = test::random_configuration(*model, rng);
      const Eigen::Isometry3d T = tool_pose(*model, q_true);
      auto r = solve_ik_nearest(*model, T, q_current);
      ASSERT_TRUE(r) << arm.name << " pose " << k << ": " << r.error().message;
      EXPECT_TRUE(r->within_limits) << arm.name;
      EXPECT_TRUE(within_limits(*model, r->q)) << arm.name << ": " << r->q.transpose();
      EXPECT_LE(pose_error(*model, r->q, T), arm.tolerance) << arm.name << " pose " << k;
      if (std::string(arm.method) == "redundant") {
        EXPECT_EQ(r->config, "redundant");
      } else {
        EXPECT_EQ(r->config.size(), 3u) << arm.name << ": " << r->config;  // "lun" ... "rdf"
      }
    }
  }
}

// Motion commands on every arm: a Cartesian target reached exactly, a target out of reach
// refused with the IK's reason.
TEST(ShippedArmsIk, CartesianTargetsOnEveryArm) {
  for (const char* name : {"puma560", "ur6", "arm7"}) {
    const RobotModelPtr model = shipped(name);
    ASSERT_TRUE(model);
    // ur6 and arm7 have "ready"; the PUMA an elbow-bent pose within its limits.
    Eigen::VectorXd bent(6);
    bent << 0.0, 0.5, -1.2, 0.0, 0.7, 0.0;
    const auto ready = model->named_configuration("ready");
    const Eigen::VectorXd start = ready ? *ready : bent;
    Eigen::Isometry3d T = tool_pose(*model, start);
    T.translation() += Eigen::Vector3d(-0.03, 0.02, -0.04);  // inwards: within reach
    const MotionOutcome out = apply_motion(*model, start, CartesianTarget{T});
    ASSERT_TRUE(out.accepted) << name << ": " << out.rejection.message;
    EXPECT_LE(pose_error(*model, out.q, T), 1e-9) << name;
    T.translation() = Eigen::Vector3d(3.0, 0.0, 0.3);
    const MotionOutcome far = apply_motion(*model, start, CartesianTarget{T});
    EXPECT_FALSE(far.accepted) << name;
    EXPECT_EQ(far.rejection.kind, RejectionKind::kUnreachable) << name;
    EXPECT_THAT(far.rejection.message, ::testing::HasSubstr("unreachable")) << name;
    EXPECT_EQ(far.q, start) << name;
  }
}

// arm7: kCurrent stays near the current pose, kRest near the rest pose: each answer is at
// least as close to its own preference as the other preference's answer is, for most poses
// (both are local minima of the self-motion, so not all), and never leaves the limits.
TEST(ShippedArmsIk, Arm7NullSpacePreferenceRestVersusCurrent) {
  const RobotModelPtr model = shipped("arm7");
  ASSERT_TRUE(model);
  const Eigen::VectorXd rest_q = *model->named_configuration("home");
  RedundancyOptions rest;
  rest.preference = NullSpacePreference::kRest;
  rest.rest_q = rest_q;
  std::mt19937_64 rng(23);
  int current_nearer = 0, rest_nearer = 0;
  const int cases = 60;
  for (int k = 0; k < cases; ++k) {
    const Eigen::VectorXd q_true = test::random_configuration(*model, rng);
    // The current pose: the generating one moved along no particular direction, so that
    // the pose's self-motion passes near it but not through it.
    Eigen::VectorXd q_current = q_true;
    for (int j = 0; j < 7; ++j) q_current[j] += 0.2 * std::sin(3.0 * j + k);
    q_current = q_current.cwiseMax(model->lower_limits()).cwiseMin(model->upper_limits());
    const Eigen::Isometry3d T = tool_pose(*model, q_true);
    auto by_current = solve_ik_nearest(*model, T, q_current);
    auto by_rest = solve_ik_nearest(*model, T, q_current, rest);
    ASSERT_TRUE(by_current && by_rest) << k;
    for (const IkSolution* s : {&*by_current, &*by_rest}) {
      EXPECT_TRUE(within_limits(*model, s->q)) << k << ": " << s->q.transpose();
      EXPECT_LE(pose_error(*model, s->q, T), 1e-9) << k;
    }
    current_nearer += (by_current->q - q_current).norm() <= (by_rest->q - q_current).norm() + 1e-9;
    rest_nearer += (by_rest->q - rest_q).norm() <= (by_current->q - rest_q).norm() + 1e-9;
  }
  EXPECT_GE(current_nearer, cases * 9 / 10);
  EXPECT_GE(rest_nearer, cases * 9 / 10);
}

// arm7: the joint-limit penalty. A preferred pose with joint 3 0.05 rad inside its upper
// limit (2.8973), within the penalty's band (0.1 of the range, 0.58 rad), is moved away from
// the limit along the self-motion (the elbow swivel, same pose); with the penalty off it
// stays.
TEST(ShippedArmsIk, Arm7KeepsAwayFromItsJointLimits) {
  const RobotModelPtr model = shipped("arm7");
  ASSERT_TRUE(model);
  Eigen::VectorXd q = *model->named_configuration("home");
  q[2] = model->upper_limits()[2] - 0.05;  // joint 3 near its upper limit (2.8973)
  const Eigen::Isometry3d T = tool_pose(*model, q);
  RedundancyOptions without;
  without.limit_weight = 0.0;
  auto stays = solve_ik_nearest(*model, T, q, without);
  auto moves = solve_ik_nearest(*model, T, q);
  ASSERT_TRUE(stays && moves);
  EXPECT_LT((stays->q - q).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_GT(model->upper_limits()[2] - moves->q[2], 0.05 + 0.01) << moves->q.transpose();
  EXPECT_TRUE(within_limits(*model, moves->q));
  EXPECT_LE(pose_error(*model, moves->q, T), 1e-9);
}

// arm7 with kRest: a Cartesian loop out and back returns to the same joints (the answer is a
// function of the pose); every step small and within the limits.
TEST(ShippedArmsIk, Arm7JogLoopWithRestPreferenceCloses) {
  const RobotModelPtr model = shipped("arm7");
  ASSERT_TRUE(model);
  const Eigen::VectorXd home = *model->named_configuration("home");
  MotionOptions options;
  options.redundancy.preference = NullSpacePreference::kRest;
  options.redundancy.rest_q = home;
  Eigen::VectorXd q = home;
  const CartesianIncrement out_step{MotionFrame::kBase, {0.01, 0.005, -0.004}, {0.0, 0.0, 0.01}};
  const CartesianIncrement back_step{MotionFrame::kBase, {-0.01, -0.005, 0.004}, {0.0, 0.0, -0.01}};
  for (const CartesianIncrement& step : {out_step, back_step}) {
    for (int k = 0; k < 15; ++k) {
      const MotionOutcome out = apply_motion(*model, q, step, options);
      ASSERT_TRUE(out.accepted) << k << ": " << out.rejection.message;
      EXPECT_EQ(out.ik_config, "redundant");
      EXPECT_TRUE(within_limits(*model, out.q));
      EXPECT_LT((out.q - q).cwiseAbs().maxCoeff(), 0.1) << k;
      q = out.q;
    }
  }
  EXPECT_LT((q - home).cwiseAbs().maxCoeff(), 1e-5) << q.transpose();
}

}  // namespace
}  // namespace telear::core
