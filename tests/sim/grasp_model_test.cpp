// The pick-and-place box of the simulated scene (telear/sim/grasp_model.hpp).
#include "telear/sim/grasp_model.hpp"

#include <gtest/gtest.h>

namespace telear::sim {
namespace {

Eigen::Isometry3d grip_at(const Eigen::Vector3d& p) {
  return Eigen::Isometry3d(Eigen::Translation3d(p));
}

TEST(GraspModelTest, ClosingOnTheBoxCarriesItAndOpeningDropsItOnTheTable) {
  GraspModel grasp;
  const Eigen::Vector3d box = SceneRenderer::workspace_object().centre_base;
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
  GraspModel grasp;
  const Eigen::Vector3d box = SceneRenderer::workspace_object().centre_base;
  grasp.update(grip_at(box + Eigen::Vector3d(0, 0, 0.05)), 0.0);
  EXPECT_FALSE(grasp.held());
  EXPECT_TRUE(grasp.T_base_object().translation().isApprox(box));
}

TEST(GraspModelTest, ReleasedBesideTheTableItFallsToTheFloor) {
  GraspModel grasp;
  const Eigen::Vector3d box = SceneRenderer::workspace_object().centre_base;
  grasp.update(grip_at(box), 0.0);
  ASSERT_TRUE(grasp.held());
  grasp.update(grip_at({0.0, 0.6, 0.5}), 0.0);
  grasp.update(grip_at({0.0, 0.6, 0.5}), 0.08);
  EXPECT_NEAR(grasp.T_base_object().translation().z(), 0.025, 1e-12);
}

}  // namespace
}  // namespace telear::sim
