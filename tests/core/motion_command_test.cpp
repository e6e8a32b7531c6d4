#include "telear/core/motion_command.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "telear/core/angles.hpp"
#include "telear/core/ik_analytic.hpp"
#include "telear/core/joint_limits.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/pose.hpp"
#include "test_util/test_util.hpp"

namespace telear::core {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kTight = 1e-9;  // m and rad: what IK round trips reach

using test::deg;

double rotation_distance(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return rotation_vector(a * b.transpose()).norm();
}

class PumaMotion : public ::testing::Test {
 protected:
  RobotModelPtr model = test::puma560();
  // A well-conditioned configuration (smallest singular value ~0.08), solution "rdf".
  const Eigen::VectorXd home = deg({10, 30, -60, 20, 40, 15});

  MotionOutcome apply(const MotionCommand& command, const MotionOptions& options = {}) const {
    return apply_motion(*model, home, command, options);
  }
  MotionOutcome apply_from(const Eigen::VectorXd& q, const MotionCommand& command,
                           const MotionOptions& options = {}) const {
    return apply_motion(*model, q, command, options);
  }
  // Checks the outcome is a rejection of `kind` that leaves the arm where it was.
  static void expect_rejected(const MotionOutcome& o, const Eigen::VectorXd& q_current,
                              RejectionKind kind) {
    EXPECT_FALSE(o.accepted);
    EXPECT_EQ(o.rejection.kind, kind) << to_string(o.rejection.kind) << ": " << o.rejection.message;
    EXPECT_EQ(o.q, q_current);  // no partial motion
    EXPECT_FALSE(o.singularity.has_value());
  }
  static void expect_accepted(const MotionOutcome& o) {
    EXPECT_TRUE(o.accepted) << o.rejection.message;
    EXPECT_EQ(o.rejection.kind, RejectionKind::kNone);
    EXPECT_TRUE(o.rejection.message.empty());
  }
};

// [SECTION] Joint commands

TEST_F(PumaMotion, JointIncrementMovesOnlyThatJoint) {
  const MotionOutcome o = apply(JointIncrement{2, radians_from_degrees(5.0)});
  expect_accepted(o);
  Eigen::VectorXd expected = home;
  expected[2] += radians_from_degrees(5.0);
  EXPECT_EQ(o.q, expected);
  EXPECT_FALSE(o.singularity.has_value());
  EXPECT_TRUE(o.ik_config.empty());
}

TEST_F(PumaMotion, JointIncrementBeyondALimitIsRejectedWhole) {
  const MotionOutcome o = apply(JointIncrement{1, radians_from_degrees(85.0)});  // 30 + 85
  expect_rejected(o, home, RejectionKind::kJointLimit);
  EXPECT_EQ(o.rejection.message,
            "joint 2 (shoulder) would be at 115.00 deg, beyond its upper limit of 110.00 deg");
  EXPECT_EQ(o.rejection.joint, 1);
  EXPECT_NEAR(o.rejection.value, radians_from_degrees(115.0), 1e-12);
  EXPECT_NEAR(o.rejection.limit, radians_from_degrees(110.0), 1e-12);

  const MotionOutcome low = apply(JointIncrement{4, radians_from_degrees(-150.0)});  // 40 - 150
  expect_rejected(low, home, RejectionKind::kJointLimit);
  EXPECT_EQ(low.rejection.message,
            "joint 5 (wrist_bend) would be at -110.00 deg, beyond its lower limit of -100.00 deg");
  EXPECT_EQ(low.rejection.joint, 4);
}

TEST_F(PumaMotion, JointIncrementWithABadIndexOrValueIsRejected) {
  for (int index : {-1, 6, 100}) {
    const MotionOutcome o = apply(JointIncrement{index, 0.1});
    expect_rejected(o, home, RejectionKind::kJointIndex);
    EXPECT_EQ(o.rejection.message, "joint index " + std::to_string(index) +
                                       " is out of range: puma560 has 6 joints (indices 0 to 5)");
    EXPECT_EQ(o.rejection.joint, -1);
    EXPECT_EQ(o.rejection.value, index);
  }
  const MotionOutcome nan = apply(JointIncrement{3, kNaN});
  expect_rejected(nan, home, RejectionKind::kInvalidInput);
  EXPECT_EQ(nan.rejection.message,
            "joint increment of joint 4 (wrist_roll) is not a finite number: nan");
  const MotionOutcome inf = apply(JointIncrement{0, -std::numeric_limits<double>::infinity()});
  expect_rejected(inf, home, RejectionKind::kInvalidInput);
  EXPECT_THAT(inf.rejection.message, HasSubstr("is not a finite number: -inf"));
}

TEST_F(PumaMotion, JointTargetIsCheckedForSizeValuesAndLimits) {
  const Eigen::VectorXd target = deg({-20, 10, 45, -90, 30, 200});
  const MotionOutcome o = apply(JointTarget{target});
  expect_accepted(o);
  EXPECT_EQ(o.q, target);

  expect_rejected(apply(JointTarget{Eigen::VectorXd::Zero(5)}), home, RejectionKind::kInvalidInput);
  EXPECT_EQ(apply(JointTarget{Eigen::VectorXd::Zero(5)}).rejection.message,
            "joint target: wrong number of joint values for robot 'puma560': expected 6, got 5");
  Eigen::VectorXd nan = target;
  nan[2] = kNaN;
  EXPECT_EQ(apply(JointTarget{nan}).rejection.message,
            "joint target: joint 3 (elbow) value is not a finite number: nan");
  const MotionOutcome beyond = apply(JointTarget{deg({-165, 10, 45, -90, 30, 200})});
  expect_rejected(beyond, home, RejectionKind::kJointLimit);
  EXPECT_EQ(beyond.rejection.message,
            "joint 1 (waist) would be at -165.00 deg, beyond its lower limit of -160.00 deg");
  EXPECT_EQ(beyond.rejection.joint, 0);
}

TEST_F(PumaMotion, AnInvalidCurrentConfigurationRejectsEveryCommand) {
  Eigen::VectorXd nan = home;
  nan[5] = kNaN;
  const std::vector<MotionCommand> commands = {JointIncrement{0, 0.1}, JointTarget{home},
                                               CartesianIncrement{},
                                               CartesianTarget{tool_pose(*model, home)}};
  for (const MotionCommand& command : commands) {
    const MotionOutcome o = apply_from(nan, command);
    EXPECT_FALSE(o.accepted);
    EXPECT_EQ(o.rejection.kind, RejectionKind::kInvalidInput);
    EXPECT_EQ(o.rejection.message,
              "current configuration: joint 6 (wrist_swivel) value is not a finite number: nan");
    const MotionOutcome short_q = apply_from(Eigen::VectorXd::Zero(3), command);
    EXPECT_EQ(short_q.rejection.message,
              "current configuration: wrong number of joint values for robot 'puma560': "
              "expected 6, got 3");
  }
}

TEST_F(PumaMotion, FromBeyondALimitOnlyMovesBackInsideAreAccepted) {
  // qn has q3 = 180 deg, beyond the elbow's 135 deg.
  const Eigen::VectorXd qn = *model->named_configuration("qn");
  const MotionOutcome other = apply_from(qn, JointIncrement{0, 0.1});
  expect_rejected(other, qn, RejectionKind::kJointLimit);
  EXPECT_EQ(other.rejection.message,
            "joint 3 (elbow) would be at 180.00 deg, beyond its upper limit of 135.00 deg");
  const MotionOutcome back = apply_from(qn, JointIncrement{2, radians_from_degrees(-50.0)});
  expect_accepted(back);
  EXPECT_NEAR(back.q[2], radians_from_degrees(130.0), 1e-12);
}

// [SECTION] Cartesian increments: each frame moves the tool as specified

class PumaCartesian : public PumaMotion {
 protected:
  // The same arm with a tool 10 cm beyond the flange and turned, so that the WRIST and TOOL
  // frames differ in origin and axes.
  RobotModel tooled = [this] {
    const Eigen::Isometry3d T_flange_tool =
        pose_from_xyz_rpy(Eigen::Vector3d(0.02, -0.01, 0.10), Eigen::Vector3d(0.3, -0.2, 0.5));
    return *model->with_tool(T_flange_tool);
  }();

  MotionOutcome increment(const RobotModel& m, MotionFrame frame, const Eigen::Vector3d& dX,
                          const Eigen::Vector3d& dM) const {
    return apply_motion(m, home, CartesianIncrement{frame, dX, dM});
  }
  static KinematicsData fk(const RobotModel& m, const Eigen::VectorXd& q) {
    KinematicsData data(m);
    forward_kinematics(m, data, q);
    return data;
  }
};

TEST_F(PumaCartesian, BaseTranslationRaisesTheToolKeepingItsOrientation) {
  const MotionOutcome o = increment(*model, MotionFrame::kBase, {0, 0, 0.01}, {0, 0, 0});
  expect_accepted(o);
  const Eigen::Isometry3d before = tool_pose(*model, home);
  const Eigen::Isometry3d after = tool_pose(*model, o.q);
  EXPECT_LT((after.translation() - before.translation() - Eigen::Vector3d(0, 0, 0.01)).norm(),
            kTight);
  EXPECT_LT(rotation_distance(after.linear(), before.linear()), kTight);
  EXPECT_EQ(o.ik_config, "rdf");  // the branch the arm is in
  EXPECT_LT((o.q - home).cwiseAbs().maxCoeff(), radians_from_degrees(5.0));
}

TEST_F(PumaCartesian, BaseRotationTurnsAboutBaseAxesThroughTheToolPoint) {
  const Eigen::Vector3d dM(0, 0, radians_from_degrees(5.0));  // about base z
  for (const RobotModel* m : {model.get(), static_cast<const RobotModel*>(&tooled)}) {
    const MotionOutcome o = increment(*m, MotionFrame::kBase, {0, 0, 0}, dM);
    expect_accepted(o);
    const Eigen::Isometry3d before = tool_pose(*m, home);
    const Eigen::Isometry3d after = tool_pose(*m, o.q);
    EXPECT_LT((after.translation() - before.translation()).norm(), kTight);
    EXPECT_LT(rotation_distance(after.linear(), rotation_from_vector(dM) * before.linear()),
              kTight);
  }
}

TEST_F(PumaCartesian, ToolTranslationMovesAlongTheToolsOwnAxes) {
  const KinematicsData before = fk(tooled, home);
  const MotionOutcome o = increment(tooled, MotionFrame::kTool, {0, 0, 0.01}, {0, 0, 0});
  expect_accepted(o);
  const Eigen::Isometry3d after = fk(tooled, o.q).T_base_tool;
  const Eigen::Vector3d tool_z = before.T_base_tool.linear().col(2);
  EXPECT_LT((after.translation() - (before.T_base_tool.translation() + 0.01 * tool_z)).norm(),
            kTight);
  EXPECT_LT(rotation_distance(after.linear(), before.T_base_tool.linear()), kTight);
}

TEST_F(PumaCartesian, ToolRotationKeepsTheToolPointFixed) {
  const Eigen::Vector3d dM(radians_from_degrees(4.0), 0, 0);  // about the tool's x
  const KinematicsData before = fk(tooled, home);
  const MotionOutcome o = increment(tooled, MotionFrame::kTool, {0, 0, 0}, dM);
  expect_accepted(o);
  const KinematicsData after = fk(tooled, o.q);
  EXPECT_LT((after.T_base_tool.translation() - before.T_base_tool.translation()).norm(), kTight);
  EXPECT_LT(rotation_distance(after.T_base_tool.linear(),
                              before.T_base_tool.linear() * rotation_from_vector(dM)),
            kTight);
  // The flange, 10 cm behind the tool point, swings.
  EXPECT_GT(
      (after.T_base_link.back().translation() - before.T_base_link.back().translation()).norm(),
      1e-3);
}

TEST_F(PumaCartesian, WristRotationKeepsTheFlangeOriginFixedAndTheToolFollows) {
  const Eigen::Vector3d dM(0, radians_from_degrees(4.0), 0);  // about the flange's y
  const KinematicsData before = fk(tooled, home);
  const MotionOutcome o = increment(tooled, MotionFrame::kWrist, {0, 0, 0}, dM);
  expect_accepted(o);
  const KinematicsData after = fk(tooled, o.q);
  const Eigen::Isometry3d& F0 = before.T_base_link.back();
  const Eigen::Isometry3d& F1 = after.T_base_link.back();
  EXPECT_LT((F1.translation() - F0.translation()).norm(), kTight);
  EXPECT_LT(rotation_distance(F1.linear(), F0.linear() * rotation_from_vector(dM)), kTight);
  // The tool point, offset from the flange, moves with it.
  EXPECT_GT((after.T_base_tool.translation() - before.T_base_tool.translation()).norm(), 1e-3);
  EXPECT_LT(
      (after.T_base_tool.matrix() - (F1 * tooled.T_flange_tool()).matrix()).cwiseAbs().maxCoeff(),
      1e-12);
}

TEST_F(PumaCartesian, WristTranslationIsAlongTheFlangeAxes) {
  const KinematicsData before = fk(tooled, home);
  const Eigen::Vector3d dX(0.01, 0.0, -0.005);
  const MotionOutcome o = increment(tooled, MotionFrame::kWrist, dX, {0, 0, 0});
  expect_accepted(o);
  const KinematicsData after = fk(tooled, o.q);
  const Eigen::Isometry3d& F0 = before.T_base_link.back();
  const Eigen::Isometry3d& F1 = after.T_base_link.back();
  EXPECT_LT((F1.translation() - (F0.translation() + F0.linear() * dX)).norm(), kTight);
  EXPECT_LT(rotation_distance(F1.linear(), F0.linear()), kTight);
}

TEST_F(PumaCartesian, FramesDifferWhenTheToolIsOffsetAndTurned) {
  // The same numbers give three different motions.
  const Eigen::Vector3d dX(0.01, 0, 0);
  const Eigen::Isometry3d base =
      tool_pose(tooled, increment(tooled, MotionFrame::kBase, dX, Eigen::Vector3d::Zero()).q);
  const Eigen::Isometry3d wrist =
      tool_pose(tooled, increment(tooled, MotionFrame::kWrist, dX, Eigen::Vector3d::Zero()).q);
  const Eigen::Isometry3d tool =
      tool_pose(tooled, increment(tooled, MotionFrame::kTool, dX, Eigen::Vector3d::Zero()).q);
  EXPECT_GT((base.translation() - wrist.translation()).norm(), 1e-3);
  EXPECT_GT((base.translation() - tool.translation()).norm(), 1e-3);
  EXPECT_GT((wrist.translation() - tool.translation()).norm(), 1e-3);
}

TEST_F(PumaCartesian, ZeroIncrementStaysPut) {
  for (MotionFrame frame : {MotionFrame::kBase, MotionFrame::kWrist, MotionFrame::kTool}) {
    const MotionOutcome o = increment(*model, frame, {0, 0, 0}, {0, 0, 0});
    expect_accepted(o);
    EXPECT_LT((o.q - home).cwiseAbs().maxCoeff(), 1e-9) << to_string(frame);
  }
}

TEST_F(PumaCartesian, NonFiniteIncrementIsRejected) {
  const MotionOutcome o = increment(*model, MotionFrame::kWrist, {0, kNaN, 0}, {0, 0, 0});
  expect_rejected(o, home, RejectionKind::kInvalidInput);
  EXPECT_EQ(o.rejection.message,
            "Cartesian increment (WRIST frame) is not finite: dX = (0, nan, 0), dM = (0, 0, 0)");
}

TEST_F(PumaCartesian, UnreachableIncrementIsRejectedWhole) {
  const MotionOutcome o = increment(*model, MotionFrame::kBase, {2.0, 0, 0}, {0, 0, 0});
  expect_rejected(o, home, RejectionKind::kUnreachable);
  EXPECT_THAT(o.rejection.message, StartsWith("target unreachable"));
  EXPECT_THAT(o.rejection.message, HasSubstr("beyond the arm's reach"));
  EXPECT_EQ(o.rejection.joint, -1);
}

// [SECTION] Cartesian targets and the choice of IK solution

TEST_F(PumaCartesian, TargetXMIsReached) {
  const Eigen::Vector3d X(0.45, -0.2, 0.5);
  const Eigen::Vector3d M(0, std::numbers::pi / 2, 0);  // tool z along base +x
  const MotionOutcome o = apply(cartesian_target(X, M));
  expect_accepted(o);
  const Eigen::Isometry3d T = tool_pose(*model, o.q);
  EXPECT_LT((T.translation() - X).norm(), kTight);
  EXPECT_LT(rotation_distance(T.linear(), rotation_from_vector(M)), kTight);
  EXPECT_FALSE(o.ik_config.empty());
}

TEST_F(PumaCartesian, TheSolutionNearestTheCurrentConfigurationIsChosen) {
  // Each in-limit solution of one pose is chosen when the arm is near it.
  const Eigen::Isometry3d T = tool_pose(*model, home);
  const AnalyticIkResult all = solve_analytic_ik(*model, *puma_geometry(*model), T);
  int checked = 0;
  for (const IkSolution& s : all.solutions) {
    if (!s.within_limits || s.singular) continue;
    Eigen::VectorXd near = s.q + Eigen::VectorXd::Constant(6, 0.02);
    ASSERT_TRUE(within_limits(*model, near)) << s.config;
    const MotionOutcome o = apply_from(near, CartesianTarget{T});
    expect_accepted(o);
    EXPECT_EQ(o.ik_config, s.config);
    EXPECT_LT((o.q - s.q).cwiseAbs().maxCoeff(), 1e-9) << s.config;
    ++checked;
  }
  EXPECT_GE(checked, 4);  // r-solutions within limits for this pose
}

TEST_F(PumaCartesian, TargetBeyondTheJointLimitsIsRejectedNamingTheJoint) {
  // Every solution of this pose needs |q5| = 120 deg or leaves another joint's limits.
  const Eigen::Isometry3d T = tool_pose(*model, deg({0, 0, 0, 0, 120, 0}));
  const MotionOutcome o = apply(CartesianTarget{T});
  expect_rejected(o, home, RejectionKind::kUnreachable);
  EXPECT_THAT(o.rejection.message, StartsWith("no IK solution within the joint limits"));
  EXPECT_THAT(o.rejection.message, HasSubstr("joint 5 (wrist_bend) would be at 120.00 deg"));
}

TEST_F(PumaCartesian, TargetThatIsNotARigidTransformIsRejected) {
  Eigen::Isometry3d T = tool_pose(*model, home);
  Eigen::Isometry3d scaled = T;
  scaled.linear() *= 1.01;
  MotionOutcome o = apply(CartesianTarget{scaled});
  expect_rejected(o, home, RejectionKind::kInvalidInput);
  EXPECT_EQ(o.rejection.message,
            "Cartesian target has a rotation block that is not orthonormal (|R R^T - I| = 0.0201, "
            "tolerance 1e-06)");
  Eigen::Isometry3d mirrored = T;
  mirrored.linear().col(2) *= -1.0;
  EXPECT_EQ(apply(CartesianTarget{mirrored}).rejection.message,
            "Cartesian target has a rotation block with determinant -1 (a reflection)");
  Eigen::Isometry3d nan = T;
  nan.translation().x() = kNaN;
  EXPECT_EQ(apply(CartesianTarget{nan}).rejection.message,
            "Cartesian target has a non-finite entry");
  Eigen::Isometry3d bottom = T;
  bottom.matrix()(3, 0) = 0.5;
  EXPECT_EQ(apply(CartesianTarget{bottom}).rejection.message,
            "Cartesian target has a bottom row other than (0, 0, 0, 1)");
  // Within the tolerance the rotation is projected onto SO(3) and the target is reached.
  Eigen::Isometry3d nearly = T;
  nearly.linear() *= 1.0 + 1e-8;
  const MotionOutcome ok = apply(CartesianTarget{nearly});
  expect_accepted(ok);
  EXPECT_LT((ok.q - home).cwiseAbs().maxCoeff(), 1e-6);
}

// [SECTION] Singularities

TEST_F(PumaMotion, WellConditionedMovesCarryNoWarning) {
  EXPECT_FALSE(apply(JointIncrement{0, 0.2}).singularity.has_value());
  EXPECT_FALSE(apply(CartesianIncrement{MotionFrame::kTool, {0, 0, 0.02}, Eigen::Vector3d::Zero()})
                   .singularity);
}

TEST_F(PumaMotion, ApproachingTheWristSingularityIsReportedAtTheEnd) {
  // q5 from 40 deg to 0.5 deg: the measure falls to about 0.37 sin(0.5 deg) ~ 0.003.
  const MotionOutcome o = apply(JointIncrement{4, radians_from_degrees(-39.5)});
  expect_accepted(o);
  ASSERT_TRUE(o.singularity.has_value());
  EXPECT_EQ(o.singularity->fraction, 1.0);
  EXPECT_GT(o.singularity->measure, 0.001);
  EXPECT_LT(o.singularity->measure, 0.005);
  EXPECT_THAT(o.singularity->message,
              StartsWith("the move passes near a singularity at the end: smallest Jacobian "
                         "singular value 0.00"));
  EXPECT_THAT(o.singularity->message, HasSubstr("(warning below 0.01)"));
}

TEST_F(PumaMotion, CrossingTheWristSingularityIsReportedOnTheWay) {
  Eigen::VectorXd from = home;
  from[4] = radians_from_degrees(30.0);
  Eigen::VectorXd to = home;
  to[4] = radians_from_degrees(-30.0);
  const MotionOutcome o = apply_from(from, JointTarget{to});
  expect_accepted(o);
  ASSERT_TRUE(o.singularity.has_value());
  // The 16 even samples step over q5 = 0 (closest at +-2 deg, measure ~0.013, above the
  // threshold); the refinement between them finds the crossing at the midpoint.
  EXPECT_NEAR(o.singularity->fraction, 0.5, 1e-6);
  EXPECT_LT(o.singularity->measure, 1e-6);
  EXPECT_THAT(o.singularity->message,
              HasSubstr("at 50% of the way: smallest Jacobian singular value"));
  // Fewer samples find it too.
  const MotionOutcome coarse = apply_from(from, JointTarget{to}, {.singularity_samples = 3});
  ASSERT_TRUE(coarse.singularity.has_value());
  EXPECT_NEAR(coarse.singularity->fraction, 0.5, 1e-6);
}

TEST_F(PumaMotion, NamedSingularConfigurationsAreReported) {
  // qz and qr have q5 = 0: joints 4 and 6 aligned.
  for (const char* name : {"qz", "qr"}) {
    const Eigen::VectorXd q = *model->named_configuration(name);
    KinematicsData data(*model);
    EXPECT_LT(jacobian_min_singular_value(*model, data, q), 1e-12) << name;
    const MotionOutcome o = apply_from(q, JointIncrement{0, 0.1});
    expect_accepted(o);
    ASSERT_TRUE(o.singularity.has_value()) << name;
    EXPECT_EQ(o.singularity->fraction, 0.0);
    EXPECT_THAT(o.singularity->message,
                StartsWith("the move passes near a singularity at the start"));
  }
  // A Cartesian move out of qr (down 1 cm) is accepted and reported.
  const Eigen::VectorXd qr = *model->named_configuration("qr");
  const MotionOutcome down = apply_from(
      qr, CartesianIncrement{MotionFrame::kBase, {0, 0, -0.01}, Eigen::Vector3d::Zero()});
  expect_accepted(down);
  EXPECT_TRUE(down.singularity.has_value());
  EXPECT_LT((tool_pose(*model, down.q).translation() - tool_pose(*model, qr).translation() -
             Eigen::Vector3d(0, 0, -0.01))
                .norm(),
            kTight);
}

TEST_F(PumaMotion, EndingAtASingularityCanBeRejectedForCartesianCommands) {
  Eigen::VectorXd singular = home;
  singular[4] = 0.0;
  const Eigen::Isometry3d T = tool_pose(*model, singular);
  const MotionOptions strict{.reject_singular_cartesian = true};
  const MotionOutcome o = apply(CartesianTarget{T}, strict);
  expect_rejected(o, home, RejectionKind::kSingular);
  EXPECT_THAT(o.rejection.message,
              StartsWith("the move would end at a singularity: smallest Jacobian singular value"));
  EXPECT_THAT(o.rejection.message, HasSubstr("is below the tolerance of 0.0001"));
  EXPECT_LT(o.rejection.value, 1e-12);
  EXPECT_EQ(o.rejection.limit, 1e-4);
  // Without the option the same move is accepted, with a warning.
  const MotionOutcome lenient = apply(CartesianTarget{T});
  expect_accepted(lenient);
  EXPECT_TRUE(lenient.singularity.has_value());
  // Joint commands are never rejected for a singularity: they are how the arm leaves one.
  expect_accepted(apply(JointTarget{singular}, strict));
}

TEST(MotionNames, FramesAndKindsHaveNames) {
  EXPECT_STREQ(to_string(MotionFrame::kBase), "BASE");
  EXPECT_STREQ(to_string(MotionFrame::kWrist), "WRIST");
  EXPECT_STREQ(to_string(MotionFrame::kTool), "TOOL");
  EXPECT_STREQ(to_string(RejectionKind::kJointLimit), "joint limit");
  EXPECT_STREQ(to_string(RejectionKind::kUnreachable), "unreachable");
}

}  // namespace
}  // namespace telear::core
