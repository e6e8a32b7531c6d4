#include "telear/session/ghost_arm.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "telear/core/joint_limits.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/pose.hpp"
#include "telear/core/robot_description.hpp"
#include "test_util/test_util.hpp"

namespace telear::session {
namespace {

TEST(GhostArm, StartsWithinTheLimitsWithTheGripperOpen) {
  GhostArm ghost(test::puma560());
  EXPECT_EQ(ghost.q(), Eigen::VectorXd::Zero(6));
  EXPECT_EQ(ghost.gripper(), 1.0);
  EXPECT_TRUE(ghost.T_base_tool().isApprox(core::tool_pose(ghost.model(), ghost.q())));
}

TEST(GhostArm, AppliesMotionCommandsAndKeepsStateOnRejection) {
  GhostArm ghost(test::puma560());
  core::MotionOutcome ok = ghost.apply(core::JointIncrement{1, 0.2});
  ASSERT_TRUE(ok.accepted) << ok.rejection.message;
  EXPECT_DOUBLE_EQ(ghost.q()[1], 0.2);
  // Cartesian increment in the tool frame: the tool moves 1 cm along its own z.
  const Eigen::Isometry3d before = ghost.T_base_tool();
  Eigen::VectorXd bent(6);
  bent << 0.0, 0.5, -1.2, 0.0, 0.7, 0.0;
  ASSERT_TRUE(ghost.apply(core::JointTarget{bent}).accepted);
  const Eigen::Isometry3d start = ghost.T_base_tool();
  core::CartesianIncrement up;
  up.frame = core::MotionFrame::kTool;
  up.dX = Eigen::Vector3d(0, 0, 0.01);
  core::MotionOutcome moved = ghost.apply(up);
  ASSERT_TRUE(moved.accepted) << moved.rejection.message;
  EXPECT_LT((ghost.T_base_tool().translation() - start * Eigen::Vector3d(0, 0, 0.01)).norm(), 1e-6);
  EXPECT_FALSE(before.isApprox(start));

  const Eigen::VectorXd q = ghost.q();
  core::MotionOutcome rejected = ghost.apply(core::JointIncrement{2, 10.0});
  EXPECT_FALSE(rejected.accepted);
  EXPECT_EQ(rejected.rejection.kind, core::RejectionKind::kJointLimit);
  EXPECT_NE(rejected.rejection.message.find("joint 3 (elbow)"), std::string::npos)
      << rejected.rejection.message;
  EXPECT_EQ(ghost.q(), q);
}

TEST(GhostArm, GoesToNamedConfigurations) {
  GhostArm ghost(test::puma560());
  core::MotionOutcome qr = ghost.go_to("qr");
  ASSERT_TRUE(qr.accepted) << qr.rejection.message;
  EXPECT_TRUE(ghost.q().isApprox(*ghost.model().named_configuration("qr")));
  const Eigen::VectorXd q = ghost.q();
  core::MotionOutcome unknown = ghost.go_to("home");
  EXPECT_FALSE(unknown.accepted);
  EXPECT_EQ(unknown.rejection.kind, core::RejectionKind::kInvalidInput);
  EXPECT_EQ(unknown.rejection.message,
            "unknown named configuration 'home' of puma560; known: qz, qr, qs, qn");
  // qn has the elbow at 180 deg, beyond the modern 135 deg limit.
  core::MotionOutcome qn = ghost.go_to("qn");
  EXPECT_FALSE(qn.accepted);
  EXPECT_EQ(qn.rejection.message.rfind("named configuration 'qn': ", 0), 0u)
      << qn.rejection.message;
  EXPECT_NE(qn.rejection.message.find("joint 3 (elbow)"), std::string::npos);
  EXPECT_EQ(ghost.q(), q);
}

TEST(GhostArm, GripperIsValidated) {
  GhostArm ghost(test::puma560());
  ASSERT_TRUE(ghost.set_gripper(0.25).ok());
  EXPECT_EQ(ghost.gripper(), 0.25);
  Status bad = ghost.set_gripper(1.5);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().message, "gripper opening 1.5 is outside 0 (closed) .. 1 (open)");
  EXPECT_FALSE(ghost.set_gripper(std::nan("")).ok());
  EXPECT_EQ(ghost.gripper(), 0.25);
}

TEST(GhostArm, ResetToTheRealRobot) {
  GhostArm ghost(test::puma560());
  Eigen::VectorXd real(6);
  real << 0.1, 0.2, -0.3, 0.4, 0.5, 0.6;
  ASSERT_TRUE(ghost.reset_to(real, 0.0).ok());
  EXPECT_EQ(ghost.q(), real);
  EXPECT_EQ(ghost.gripper(), 0.0);
  // Rounding just beyond a limit is clamped onto it.
  Eigen::VectorXd at_limit = real;
  at_limit[1] = ghost.model().upper_limits()[1] + 1e-9;
  ASSERT_TRUE(ghost.reset_to(at_limit).ok());
  EXPECT_EQ(ghost.q()[1], ghost.model().upper_limits()[1]);

  Status wrong_size = ghost.reset_to(Eigen::VectorXd::Zero(5));
  ASSERT_FALSE(wrong_size.ok());
  EXPECT_EQ(wrong_size.error().message.rfind("ghost = real: ", 0), 0u);
  Eigen::VectorXd beyond = real;
  beyond[2] = 3.0;
  Status limit = ghost.reset_to(beyond);
  ASSERT_FALSE(limit.ok());
  EXPECT_NE(limit.error().message.find("joint 3 (elbow) would be at 171.89 deg"), std::string::npos)
      << limit.error().message;
  Status gripper = ghost.reset_to(real, -0.1);
  EXPECT_FALSE(gripper.ok());
  EXPECT_EQ(ghost.q()[2], real[2]);  // unchanged by the failed resets

  auto created = GhostArm::create(test::puma560(), beyond);
  ASSERT_FALSE(created.ok());
  EXPECT_NE(created.error().message.find("beyond its upper limit"), std::string::npos);
}

// The shipped URDF arms as ghosts (issue 12): Cartesian jogs in the base, wrist and tool
// frames reach the pose each increment asks for (core::incremented_tool_pose), stay within
// the limits and move the joints a little per step; ur6 through its closed form (a branch
// label), arm7 (7 joints) through the null-space search ("redundant").
core::RobotModelPtr shipped_arm(const std::string& name) {
  auto d = core::load_robot_description({name, "", {}});
  EXPECT_TRUE(d) << d.error().message;
  return d ? d->model : nullptr;
}

void expect_cartesian_jogs(const std::string& name, const std::string& config_kind) {
  const core::RobotModelPtr model = shipped_arm(name);
  ASSERT_TRUE(model);
  const Eigen::VectorXd ready = *model->named_configuration("ready");
  for (core::MotionFrame frame :
       {core::MotionFrame::kBase, core::MotionFrame::kWrist, core::MotionFrame::kTool}) {
    auto ghost = GhostArm::create(model, ready);
    ASSERT_TRUE(ghost.ok()) << ghost.error().message;
    const core::CartesianIncrement step{frame, {0.004, -0.003, 0.005}, {0.01, -0.02, 0.015}};
    for (int k = 0; k < 20; ++k) {
      core::KinematicsData data(*model);
      core::forward_kinematics(*model, data, ghost->q());
      const Eigen::Isometry3d expected = core::incremented_tool_pose(*model, data, step);
      const Eigen::VectorXd before = ghost->q();
      const core::MotionOutcome out = ghost->apply(step);
      ASSERT_TRUE(out.accepted) << name << " " << core::to_string(frame) << " step " << k << ": "
                                << out.rejection.message;
      if (config_kind == "redundant") {
        EXPECT_EQ(out.ik_config, "redundant");
      } else {
        EXPECT_EQ(out.ik_config.size(), 3u) << out.ik_config;  // "lun" ... "rdf"
      }
      EXPECT_EQ(ghost->q(), out.q);
      EXPECT_TRUE(core::within_limits(*model, ghost->q()));
      const core::Vector6d e = core::pose_error_in_base(ghost->T_base_tool(), expected);
      EXPECT_LT(e.head<3>().norm(), 1e-9) << name << " " << core::to_string(frame) << " " << k;
      EXPECT_LT(e.tail<3>().norm(), 1e-9) << name << " " << core::to_string(frame) << " " << k;
      EXPECT_LT((ghost->q() - before).cwiseAbs().maxCoeff(), 0.1)
          << name << " " << core::to_string(frame) << " step " << k;
    }
  }
}

TEST(GhostArm, CartesianJogOfTheSevenJointArmInBaseWristAndToolFrames) {
  expect_cartesian_jogs("arm7", "redundant");
}

TEST(GhostArm, CartesianJogOfTheUrArmInBaseWristAndToolFrames) {
  expect_cartesian_jogs("ur6", "closed form");
}

// The 7-joint ghost with the rest-pose preference (MotionOptions::redundancy): jogged out
// along a line in the tool frame and back, it comes back to the same joints; a jog beyond
// reach is refused and leaves the ghost where it was.
TEST(GhostArm, SevenJointGhostWithRestPreferenceComesBackAndRefusesTheUnreachable) {
  const core::RobotModelPtr model = shipped_arm("arm7");
  ASSERT_TRUE(model);
  const Eigen::VectorXd home = *model->named_configuration("home");
  core::MotionOptions options;
  options.redundancy.preference = core::NullSpacePreference::kRest;
  options.redundancy.rest_q = home;
  auto ghost = GhostArm::create(model, home, 1.0, options);
  ASSERT_TRUE(ghost.ok()) << ghost.error().message;
  // Pure translations: the tool's axes do not turn, so the way back undoes the way out.
  const core::CartesianIncrement out{core::MotionFrame::kTool, {0.01, 0.0, 0.008}, {0, 0, 0}};
  const core::CartesianIncrement back{core::MotionFrame::kTool, {-0.01, 0.0, -0.008}, {0, 0, 0}};
  const Eigen::Isometry3d start = ghost->T_base_tool();
  for (int k = 0; k < 10; ++k) ASSERT_TRUE(ghost->apply(out).accepted) << k;
  EXPECT_GT((ghost->T_base_tool().translation() - start.translation()).norm(), 0.1);
  for (int k = 0; k < 10; ++k) ASSERT_TRUE(ghost->apply(back).accepted) << k;
  // Back at the pose, and with kRest the joints are a function of the pose: back home.
  EXPECT_LT((ghost->T_base_tool().translation() - start.translation()).norm(), 1e-9);
  EXPECT_LT((ghost->q() - home).cwiseAbs().maxCoeff(), 1e-5) << ghost->q().transpose();

  const Eigen::VectorXd q = ghost->q();
  core::CartesianTarget far;
  far.T_base_tool = ghost->T_base_tool();
  far.T_base_tool.translation() = Eigen::Vector3d(2.0, 0.0, 0.4);
  const core::MotionOutcome refused = ghost->apply(far);
  EXPECT_FALSE(refused.accepted);
  EXPECT_EQ(refused.rejection.kind, core::RejectionKind::kUnreachable);
  EXPECT_EQ(ghost->q(), q);
}

}  // namespace
}  // namespace telear::session
