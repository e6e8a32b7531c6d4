// geometry/robot_selection.hpp: the robot options every command and `telear bench kin` share,
// as plain fields -- the robot spec they name and the mesh policy, whose error names the field.

#include "telear/geometry/robot_selection.hpp"

#include <gtest/gtest.h>

namespace telear::geometry {
namespace {

TEST(RobotSelection, NamesTheRobotTipAndPackagePaths) {
  RobotSelection selection;
  EXPECT_EQ(selection.robot, "puma560");
  selection.robot = "arm.urdf";
  selection.tip = "tcp";
  selection.package_paths = {"/a", "/b"};
  const core::RobotSpec spec = selection.robot_spec();
  EXPECT_EQ(spec.name_or_path, "arm.urdf");
  EXPECT_EQ(spec.tip, "tcp");
  EXPECT_EQ(spec.package_paths, (std::vector<std::string>{"/a", "/b"}));
}

TEST(RobotSelection, TurnsTheMeshPolicyIntoGeometryOptions) {
  RobotSelection selection;
  selection.package_paths = {"/pkgs"};
  auto options = selection.geometry_options();
  ASSERT_TRUE(options) << options.error().message;
  EXPECT_EQ(options->missing_meshes, MissingMeshes::kError);
  EXPECT_EQ(options->package_paths, (std::vector<std::string>{"/pkgs"}));
  selection.missing_meshes = "primitives";
  options = selection.geometry_options();
  ASSERT_TRUE(options) << options.error().message;
  EXPECT_EQ(options->missing_meshes, MissingMeshes::kPrimitives);
}

TEST(RobotSelection, RefusesAnUnknownMeshPolicyNamingTheField) {
  RobotSelection selection;
  selection.missing_meshes = "maybe";
  const auto options = selection.geometry_options();
  ASSERT_FALSE(options);
  EXPECT_EQ(options.error().message, "missing_meshes: 'maybe' is not error or primitives");
}

}  // namespace
}  // namespace telear::geometry
