#include "telear/session/ghost_arm.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "telear/core/kinematics.hpp"
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

}  // namespace
}  // namespace telear::session
