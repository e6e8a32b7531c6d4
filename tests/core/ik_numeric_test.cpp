#include "telear/core/ik_numeric.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <random>

#include "telear/core/joint_limits.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/robot_loader.hpp"
#include "test_util/test_util.hpp"

namespace telear::core {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

// A 6-joint arm outside the PUMA class: UR-like, shoulder and elbow axes along y, a wrist
// whose axes do not meet, a continuous last joint and a fixed tool joint.
constexpr const char* kUrLikeUrdf = R"(<?xml version="1.0"?>
<robot name="ur_like">
  <link name="base"/>
  <joint name="pan" type="revolute"><parent link="base"/><child link="l1"/>
    <origin xyz="0 0 0.089"/><axis xyz="0 0 1"/>
    <limit lower="-3.0" upper="3.0" effort="1" velocity="2"/></joint>
  <link name="l1"/>
  <joint name="lift" type="revolute"><parent link="l1"/><child link="l2"/>
    <origin xyz="0 0.136 0" rpy="0 1.5707963 0"/><axis xyz="0 1 0"/>
    <limit lower="-3.0" upper="3.0" effort="1" velocity="2"/></joint>
  <link name="l2"/>
  <joint name="elbow" type="revolute"><parent link="l2"/><child link="l3"/>
    <origin xyz="0 -0.12 0.425"/><axis xyz="0 1 0"/>
    <limit lower="-2.8" upper="2.8" effort="1" velocity="2"/></joint>
  <link name="l3"/>
  <joint name="wrist1" type="revolute"><parent link="l3"/><child link="l4"/>
    <origin xyz="0 0 0.392" rpy="0 1.5707963 0"/><axis xyz="0 1 0"/>
    <limit lower="-3.0" upper="3.0" effort="1" velocity="2"/></joint>
  <link name="l4"/>
  <joint name="wrist2" type="revolute"><parent link="l4"/><child link="l5"/>
    <origin xyz="0 0.093 0"/><axis xyz="0 0 1"/>
    <limit lower="-3.0" upper="3.0" effort="1" velocity="2"/></joint>
  <link name="l5"/>
  <joint name="wrist3" type="continuous"><parent link="l5"/><child link="l6"/>
    <origin xyz="0 0 0.095"/><axis xyz="0 1 0"/></joint>
  <link name="l6"/>
  <joint name="tool" type="fixed"><parent link="l6"/><child link="tcp"/>
    <origin xyz="0 0.082 0" rpy="-1.5707963 0 0"/></joint>
  <link name="tcp"/>
</robot>
)";

// A 4-joint SCARA-like arm with a prismatic joint: targets lie on a 4-D manifold of poses.
constexpr const char* kScaraUrdf = R"(<?xml version="1.0"?>
<robot name="scara">
  <link name="base"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/>
    <origin xyz="0 0 0.4"/><axis xyz="0 0 1"/>
    <limit lower="-2.5" upper="2.5" effort="1" velocity="2"/></joint>
  <link name="l1"/>
  <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/>
    <origin xyz="0.35 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-2.5" upper="2.5" effort="1" velocity="2"/></joint>
  <link name="l2"/>
  <joint name="j3" type="prismatic"><parent link="l2"/><child link="l3"/>
    <origin xyz="0.3 0 0"/><axis xyz="0 0 -1"/>
    <limit lower="0" upper="0.2" effort="1" velocity="0.5"/></joint>
  <link name="l3"/>
  <joint name="j4" type="revolute"><parent link="l3"/><child link="l4"/>
    <origin xyz="0 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-3.0" upper="3.0" effort="1" velocity="2"/></joint>
  <link name="l4"/>
</robot>
)";

RobotModel parse(const char* text, const char* name) {
  auto model = parse_urdf(text, name);
  EXPECT_TRUE(model) << model.error().message;
  return std::move(model).value();
}

struct Tally {
  int solved = 0;
  int trials = 0;
  long iterations = 0;
};

// Cold-start solves of `trials` targets from random in-limit configurations; every success
// must reproduce the target within the tolerances and stay within the limits.
Tally solve_random_targets(const RobotModel& model, int trials, std::uint64_t seed,
                           NumericIkOptions options = {}) {
  std::mt19937_64 rng(seed);
  NumericIkSolver solver(model, options);
  KinematicsData data(model);
  Tally tally;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model.dof());
  for (int trial = 0; trial < trials; ++trial) {
    const Eigen::VectorXd q_target = test::random_configuration(model, rng);
    forward_kinematics(model, data, q_target);
    const Eigen::Isometry3d T = data.T_base_tool;
    const NumericIkResult r = solver.solve(T, zero);
    ++tally.trials;
    tally.iterations += r.iterations;
    EXPECT_TRUE(within_limits(model, r.q)) << "trial " << trial;
    if (!r.success) {
      EXPECT_FALSE(r.message.empty());
      continue;
    }
    ++tally.solved;
    EXPECT_TRUE(r.message.empty());
    forward_kinematics(model, data, r.q);
    const Vector6d e = pose_error_in_base(data.T_base_tool, T);
    EXPECT_LE(e.head<3>().norm(), options.position_tolerance_m * 1.0001) << "trial " << trial;
    EXPECT_LE(e.tail<3>().norm(), options.orientation_tolerance_rad * 1.0001) << "trial " << trial;
    EXPECT_NEAR(r.position_error_m, e.head<3>().norm(), 1e-12);
  }
  return tally;
}

TEST(NumericIk, SolvesThePumaFromUrdfColdStart) {
  auto loaded = load_robot(test::data_path("robots/puma560.urdf"));
  ASSERT_TRUE(loaded) << loaded.error().message;
  const Tally t = solve_random_targets(**loaded, 10000, 20240602);
  // The requirement: at least 99.9 % of reachable poses, from the zero configuration.
  EXPECT_GE(t.solved, 9990) << "solved " << t.solved << " of " << t.trials;
  RecordProperty("solved", t.solved);
  RecordProperty("mean_iterations", std::to_string(double(t.iterations) / t.trials));
}

TEST(NumericIk, SolvesAnArmOutsideThePumaClass) {
  const RobotModel model = parse(kUrLikeUrdf, "ur_like.urdf");
  const Tally t = solve_random_targets(model, 2000, 11);
  EXPECT_GE(t.solved, 1996) << "solved " << t.solved << " of " << t.trials;
}

TEST(NumericIk, SolvesAFourJointArmWithAPrismaticJoint) {
  const RobotModel model = parse(kScaraUrdf, "scara.urdf");
  ASSERT_EQ(model.dof(), 4);
  const Tally t = solve_random_targets(model, 1000, 12);
  EXPECT_GE(t.solved, 998) << "solved " << t.solved << " of " << t.trials;
}

TEST(NumericIk, UnreachableTargetReportsResidualAndStaysWithinLimits) {
  const auto model = test::puma560();
  ASSERT_TRUE(model);
  NumericIkOptions options;
  options.max_restarts = 5;
  NumericIkSolver solver(*model, options);
  Eigen::Isometry3d far = Eigen::Isometry3d::Identity();
  far.translation() = Eigen::Vector3d(2.0, 0.0, 0.5);
  const NumericIkResult r = solver.solve(far, Eigen::VectorXd::Zero(6));
  EXPECT_FALSE(r.success);
  EXPECT_EQ(r.restarts, 5);
  EXPECT_GT(r.iterations, 0);
  EXPECT_GT(r.position_error_m, 1.0);
  EXPECT_TRUE(within_limits(*model, r.q));
  EXPECT_THAT(r.message, StartsWith("no configuration within the joint limits reaches it after "
                                    "6 attempts ("));
  EXPECT_THAT(r.message, HasSubstr(" iterations); the closest is "));
  // The residual reported is that of the configuration returned.
  const Vector6d e = pose_error_in_base(tool_pose(*model, r.q), far);
  EXPECT_NEAR(r.position_error_m, e.head<3>().norm(), 1e-12);
  EXPECT_NEAR(r.orientation_error_rad, e.tail<3>().norm(), 1e-12);
}

TEST(NumericIk, NonFiniteTargetIsRejected) {
  const auto model = test::puma560();
  NumericIkSolver solver(*model);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T(0, 3) = std::numeric_limits<double>::infinity();
  const NumericIkResult r = solver.solve(T, Eigen::VectorXd::Zero(6));
  EXPECT_FALSE(r.success);
  EXPECT_EQ(r.message, "target pose or seed is not finite");
}

TEST(NumericIk, SolvesAreReproducibleWhateverCameBefore) {
  const auto model = test::puma560();
  std::mt19937_64 rng(5);
  const Eigen::Isometry3d T = tool_pose(*model, test::random_configuration(*model, rng));
  const Eigen::Isometry3d other = tool_pose(*model, test::random_configuration(*model, rng));
  NumericIkSolver a(*model), b(*model);
  const NumericIkResult first = a.solve(T, Eigen::VectorXd::Zero(6));
  (void)b.solve(other, Eigen::VectorXd::Zero(6));
  const NumericIkResult second = b.solve(T, Eigen::VectorXd::Zero(6));
  EXPECT_TRUE(first.success);
  EXPECT_EQ(first.q, second.q);
  EXPECT_EQ(first.iterations, second.iterations);
  EXPECT_EQ(first.restarts, second.restarts);
}

TEST(NumericIk, ASeedNearTheAnswerConvergesToIt) {
  const auto model = test::puma560();
  Eigen::VectorXd q(6);
  q << 0.3, -0.5, 0.4, 1.0, -0.7, 0.2;
  NumericIkSolver solver(*model);
  Eigen::VectorXd seed = q;
  seed.array() += 0.05;
  const NumericIkResult r = solver.solve(tool_pose(*model, q), seed);
  ASSERT_TRUE(r.success) << r.message;
  EXPECT_EQ(r.restarts, 0);
  EXPECT_LT((r.q - q).cwiseAbs().maxCoeff(), 1e-5);
  EXPECT_LE(r.position_error_m, 1e-6);
  EXPECT_LE(r.orientation_error_rad, 1e-6);
}

}  // namespace
}  // namespace telear::core
