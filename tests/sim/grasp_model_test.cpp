// The pick-and-place box of the simulated scene (telear/sim/grasp_model.hpp).
#include "telear/sim/grasp_model.hpp"

#include <gtest/gtest.h>

#include "telear/core/workspace.hpp"

namespace telear::sim {
namespace {

Eigen::Isometry3d grip_at(const Eigen::Vector3d& p) {
  return Eigen::Isometry3d(Eigen::Translation3d(p));
}

// The PUMA's shipped workspace: the table top (upper face at z = 0.40) and the 5 cm box on it.
core::Workspace shipped_workspace() {
  auto workspace = core::load_workspace_file(core::default_workspace_file("puma560"));
  EXPECT_TRUE(workspace) << workspace.error().message;
  return workspace ? *workspace : core::Workspace{};
}

GraspModel shipped_grasp() {
  auto grasp = GraspModel::create(shipped_workspace());
  EXPECT_TRUE(grasp) << grasp.error().message;
  return grasp ? *grasp : GraspModel{};
}

Eigen::Vector3d box_centre() {
  return shipped_workspace().find("box")->T_base_object.translation();
}

TEST(GraspModelTest, ClosingOnTheBoxCarriesItAndOpeningDropsItOnTheTable) {
  GraspModel grasp = shipped_grasp();
  const Eigen::Vector3d box = box_centre();
  // Open gripper at the box: nothing happens.
  grasp.update(grip_at(box), 0.08);
  EXPECT_FALSE(grasp.held());
  // Closed: held, the fingers stop at the box's edge.
  grasp.update(grip_at(box + Eigen::Vector3d(0.005, 0, 0)), 0.0);
  ASSERT_TRUE(grasp.held());
  EXPECT_EQ(grasp.grasps(), 1);
  EXPECT_DOUBLE_EQ(grasp.rendered_opening(0.0), 0.05);
  // Carried: lift and move; the box keeps its offset from the gripper.
  const Eigen::Vector3d above(0.55, -0.2, 0.6);
  grasp.update(grip_at(above), 0.0);
  EXPECT_TRUE(grasp.T_base_object().translation().isApprox(above - Eigen::Vector3d(0.005, 0, 0)));
  // Opened over the table: dropped onto its top, upright.
  grasp.update(grip_at(above), 0.08);
  EXPECT_FALSE(grasp.held());
  EXPECT_NEAR(grasp.T_base_object().translation().z(), 0.425, 1e-12);
  EXPECT_NEAR(grasp.T_base_object().translation().y(), -0.2, 1e-12);
  EXPECT_DOUBLE_EQ(grasp.rendered_opening(0.0), 0.0);
}

TEST(GraspModelTest, ClosingAwayFromTheBoxGraspsNothing) {
  GraspModel grasp = shipped_grasp();
  const Eigen::Vector3d box = box_centre();
  grasp.update(grip_at(box + Eigen::Vector3d(0, 0, 0.05)), 0.0);
  EXPECT_FALSE(grasp.held());
  EXPECT_TRUE(grasp.T_base_object().translation().isApprox(box));
}

TEST(GraspModelTest, ReleasedBesideTheTableItFallsToTheFloor) {
  GraspModel grasp = shipped_grasp();
  const Eigen::Vector3d box = box_centre();
  grasp.update(grip_at(box), 0.0);
  ASSERT_TRUE(grasp.held());
  grasp.update(grip_at({0.0, 0.6, 0.5}), 0.0);
  grasp.update(grip_at({0.0, 0.6, 0.5}), 0.08);
  EXPECT_NEAR(grasp.T_base_object().translation().z(), 0.025, 1e-12);
}

TEST(GraspModelTest, AWorkspaceWithNothingGraspableIsRefusedWithItsName) {
  core::Workspace workspace = shipped_workspace();
  workspace.objects.pop_back();  // the box
  auto grasp = GraspModel::create(workspace);
  ASSERT_FALSE(grasp);
  EXPECT_NE(grasp.error().message.find("puma560_table.yaml has no graspable object"),
            std::string::npos)
      << grasp.error().message;
}

}  // namespace
}  // namespace telear::sim
