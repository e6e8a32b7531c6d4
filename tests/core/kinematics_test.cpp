#include "telear/core/kinematics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "telear/core/robot_loader.hpp"
#include "test_util/test_util.hpp"

namespace telear::core {
namespace {

using test::dh_product;
using test::max_abs_diff;

class PumaKinematics : public ::testing::Test {
 protected:
  RobotModelPtr model = test::puma560();
};

TEST_F(PumaKinematics, NamedConfigurationsMatchIndependentDhProduct) {
  ASSERT_TRUE(model);
  ASSERT_TRUE(model->dh().has_value());
  for (const char* name : {"qz", "qr", "qs", "qn"}) {
    const auto q = model->named_configuration(name);
    ASSERT_TRUE(q.has_value()) << name;
    EXPECT_LT(max_abs_diff(tool_pose(*model, *q).matrix(), dh_product(*model->dh(), *q)), 1e-12)
        << name;
  }
}

TEST_F(PumaKinematics, ZeroConfigurationIsTheKnownPose) {
  // At qz the PUMA's tool sits at x = a2 + a3, y = -d3 (shoulder offset along -y),
  // z = d1 + d4, with the base orientation (Robotics Toolbox: puma.fkine(puma.qz)).
  const Eigen::Isometry3d T = tool_pose(*model, Eigen::VectorXd::Zero(6));
  EXPECT_NEAR(T.translation().x(), 0.4318 + 0.0203, 1e-12);
  EXPECT_NEAR(T.translation().y(), -0.15005, 1e-12);
  EXPECT_NEAR(T.translation().z(), 0.67183 + 0.4318, 1e-12);
  EXPECT_LT((T.linear() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-12);
}

TEST_F(PumaKinematics, MatchesTheRoboticsToolboxPublishedPoseAtQn) {
  // Corke's RVC3-python README prints puma.fkine(puma.qn) for the toolbox's DH.Puma560
  // (pedestal included), to four decimals:
  //    0  0  1   0.5963
  //    0  1  0  -0.1501
  //   -1  0  0   0.6575
  // and ikine_LM's answer q = (7.235e-08, -0.8335, 0.09396, 3.142, 0.8312, -3.142) for it.
  const Eigen::Isometry3d T = tool_pose(*model, *model->named_configuration("qn"));
  // Half a unit of the fourth decimal, plus a hair: y = -d3 = -0.15005 exactly, which the
  // printout rounds to -0.1501.
  const double printed = 5e-5 + 1e-12;
  EXPECT_NEAR(T.translation().x(), 0.5963, printed);
  EXPECT_NEAR(T.translation().y(), -0.1501, printed);
  EXPECT_NEAR(T.translation().z(), 0.6575, printed);
  Eigen::Matrix3d R_expected;
  R_expected << 0, 0, 1, 0, 1, 0, -1, 0, 0;
  EXPECT_LT((T.linear() - R_expected).cwiseAbs().maxCoeff(), 1e-12);
  Eigen::VectorXd q_toolbox(6);
  q_toolbox << 7.235e-08, -0.8335, 0.09396, 3.142, 0.8312, -3.142;
  const Eigen::Isometry3d T_toolbox = tool_pose(*model, q_toolbox);
  EXPECT_LT((T_toolbox.translation() - T.translation()).norm(), 1e-3);  // 4-digit q printout
}

TEST_F(PumaKinematics, RandomConfigurationsMatchIndependentDhProduct) {
  std::mt19937_64 rng(42);
  KinematicsData data(*model);
  for (int trial = 0; trial < 1000; ++trial) {
    const Eigen::VectorXd q = test::random_configuration(*model, rng);
    forward_kinematics(*model, data, q);
    ASSERT_LT(max_abs_diff(data.T_base_tool.matrix(), dh_product(*model->dh(), q)), 1e-12);
    // Every intermediate frame is the product of the first i rows.
    for (int i = 1; i <= 6; ++i) {
      std::vector<DhRow> prefix(model->dh()->begin(), model->dh()->begin() + i);
      ASSERT_LT(max_abs_diff(data.T_base_link[static_cast<size_t>(i)].matrix(),
                             dh_product(prefix, q.head(i))),
                1e-12);
    }
  }
}

TEST_F(PumaKinematics, IncrementalUpdateRecomputesOnlyDownstreamFramesAndEqualsFullFk) {
  std::mt19937_64 rng(7);
  KinematicsData incremental(*model);
  KinematicsData full(*model);
  forward_kinematics(*model, incremental, test::random_configuration(*model, rng));
  for (int trial = 0; trial < 500; ++trial) {
    const int joint = static_cast<int>(rng() % 6);
    const std::vector<Eigen::Isometry3d> before = incremental.T_base_link;
    const double value = test::random_configuration(*model, rng)[joint];
    set_joint(*model, incremental, joint, value);
    EXPECT_EQ(incremental.last_first_updated_joint, joint);
    EXPECT_EQ(incremental.last_frames_recomputed, 6 - joint);
    // Frames upstream of the joint are untouched, bit for bit.
    for (int i = 0; i <= joint; ++i) {
      ASSERT_TRUE(incremental.T_base_link[static_cast<size_t>(i)].matrix() ==
                  before[static_cast<size_t>(i)].matrix());
    }
    forward_kinematics(*model, full, incremental.q);
    for (size_t i = 0; i < full.T_base_link.size(); ++i) {
      ASSERT_LT(max_abs_diff(full.T_base_link[i].matrix(), incremental.T_base_link[i].matrix()),
                1e-15);
    }
    ASSERT_LT(max_abs_diff(full.T_base_tool.matrix(), incremental.T_base_tool.matrix()), 1e-15);
  }
}

TEST_F(PumaKinematics, UpdateKinematicsStartsAtTheFirstChangedJoint) {
  KinematicsData data(*model);
  Eigen::VectorXd q = *model->named_configuration("qr");
  update_kinematics(*model, data, q);  // first call: full
  EXPECT_EQ(data.last_frames_recomputed, 6);
  q[4] += 0.1;
  update_kinematics(*model, data, q);
  EXPECT_EQ(data.last_first_updated_joint, 4);
  EXPECT_EQ(data.last_frames_recomputed, 2);
  update_kinematics(*model, data, q);
  EXPECT_EQ(data.last_frames_recomputed, 0);
  EXPECT_LT(max_abs_diff(data.T_base_tool.matrix(), dh_product(*model->dh(), q)), 1e-12);
}

// Central finite differences of the tool pose, as a base-frame twist per joint.
Jacobian finite_difference_jacobian(const RobotModel& model, const Eigen::VectorXd& q) {
  const double h = 1e-6;
  Jacobian J(6, model.dof());
  for (int i = 0; i < model.dof(); ++i) {
    Eigen::VectorXd qp = q, qm = q;
    qp[i] += h;
    qm[i] -= h;
    const Eigen::Isometry3d Tp = tool_pose(model, qp), Tm = tool_pose(model, qm);
    J.block<3, 1>(0, i) = (Tp.translation() - Tm.translation()) / (2 * h);
    J.block<3, 1>(3, i) = rotation_vector(Tp.linear() * Tm.linear().transpose()) / (2 * h);
  }
  return J;
}

TEST_F(PumaKinematics, JacobianMatchesFiniteDifferencesInBaseAndToolFrames) {
  std::mt19937_64 rng(3);
  KinematicsData data(*model);
  Jacobian J_base, J_tool;
  // A tool offset makes the linear part depend on the tool point, not just the flange.
  const RobotModel with_tool =
      *model->with_tool(pose_from_xyz_rpy({0.01, -0.02, 0.15}, {0.1, 0.2, 0.3}));
  KinematicsData tool_data(with_tool);
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::VectorXd q = test::random_configuration(*model, rng);
    forward_kinematics(with_tool, tool_data, q);
    geometric_jacobian(with_tool, tool_data, JacobianFrame::kBase, J_base);
    const Jacobian J_fd = finite_difference_jacobian(with_tool, q);
    ASSERT_LT((J_base - J_fd).cwiseAbs().maxCoeff(), 1e-7) << "trial " << trial;
    geometric_jacobian(with_tool, tool_data, JacobianFrame::kTool, J_tool);
    const Eigen::Matrix3d R = tool_data.T_base_tool.linear();
    ASSERT_LT((R * J_tool.topRows<3>() - J_base.topRows<3>()).cwiseAbs().maxCoeff(), 1e-12);
    ASSERT_LT((R * J_tool.bottomRows<3>() - J_base.bottomRows<3>()).cwiseAbs().maxCoeff(), 1e-12);
  }
  forward_kinematics(*model, data, *model->named_configuration("qn"));
  geometric_jacobian(*model, data, JacobianFrame::kBase, J_base);
  EXPECT_LT((J_base - finite_difference_jacobian(*model, data.q)).cwiseAbs().maxCoeff(), 1e-7);
}

TEST_F(PumaKinematics, UrdfAndDhModelsAgree) {
  auto urdf = load_robot(test::data_path("robots/puma560.urdf"));
  ASSERT_TRUE(urdf) << urdf.error().message;
  const RobotModel& u = **urdf;
  ASSERT_EQ(u.dof(), 6);
  EXPECT_EQ(u.joint(1).name, "shoulder");
  EXPECT_LT((u.lower_limits() - model->lower_limits()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((u.max_velocities() - model->max_velocities()).cwiseAbs().maxCoeff(), 1e-12);
  std::mt19937_64 rng(11);
  KinematicsData du(u), dd(*model);
  Jacobian Ju, Jd;
  for (int trial = 0; trial < 500; ++trial) {
    const Eigen::VectorXd q = test::random_configuration(*model, rng);
    forward_kinematics(u, du, q);
    forward_kinematics(*model, dd, q);
    ASSERT_LT(max_abs_diff(du.T_base_tool.matrix(), dd.T_base_tool.matrix()), 1e-12);
    geometric_jacobian(u, du, JacobianFrame::kBase, Ju);
    geometric_jacobian(*model, dd, JacobianFrame::kBase, Jd);
    ASSERT_LT((Ju - Jd).cwiseAbs().maxCoeff(), 1e-12);
  }
}

TEST_F(PumaKinematics, CheckJointVectorRejectsWrongSizeAndNaN) {
  EXPECT_TRUE(check_joint_vector(*model, Eigen::VectorXd::Zero(6)).ok());
  const Status wrong_size = check_joint_vector(*model, Eigen::VectorXd::Zero(7));
  ASSERT_FALSE(wrong_size.ok());
  EXPECT_EQ(wrong_size.error().message,
            "wrong number of joint values for robot 'puma560': expected 6, got 7");
  Eigen::VectorXd q = Eigen::VectorXd::Zero(6);
  q[2] = std::numeric_limits<double>::quiet_NaN();
  const Status nan = check_joint_vector(*model, q);
  ASSERT_FALSE(nan.ok());
  EXPECT_EQ(nan.error().message, "joint 3 (elbow) value is not a finite number: nan");
}

}  // namespace
}  // namespace telear::core
