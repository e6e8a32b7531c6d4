// The registration marker's mount (include/telear/core/marker_mount.hpp): the PUMA's shipped
// file, its corners in the flange frame, and bad files refused with the field named.
#include "telear/core/marker_mount.hpp"

#include <gtest/gtest.h>

#include "telear/core/robot_loader.hpp"

namespace telear::core {
namespace {

TEST(MarkerMountTest, ThePumasMarkerFacesPlusX6BesideThePalm) {
  auto model = load_robot("puma560");
  ASSERT_TRUE(model) << model.error().message;
  auto mount = marker_mount_for(**model);
  ASSERT_TRUE(mount) << mount.error().message;
  EXPECT_EQ(mount->dictionary, "DICT_4X4_50");
  EXPECT_EQ(mount->id, 0);
  EXPECT_DOUBLE_EQ(mount->side_m, 0.1);
  // x_marker = y6, y_marker = z6, z_marker (the face normal) = x6.
  const Eigen::Matrix3d R = mount->T_flange_marker.linear();
  EXPECT_TRUE(R.col(0).isApprox(Eigen::Vector3d::UnitY(), 1e-12));
  EXPECT_TRUE(R.col(1).isApprox(Eigen::Vector3d::UnitZ(), 1e-12));
  EXPECT_TRUE(R.col(2).isApprox(Eigen::Vector3d::UnitX(), 1e-12));
  // Corners in the detector's order: top-left, top-right, bottom-right, bottom-left.
  const auto corners = mount->corners_flange();
  EXPECT_TRUE(corners[0].isApprox(Eigen::Vector3d(0.05, -0.05, 0.12), 1e-12));
  EXPECT_TRUE(corners[1].isApprox(Eigen::Vector3d(0.05, 0.05, 0.12), 1e-12));
  EXPECT_TRUE(corners[2].isApprox(Eigen::Vector3d(0.05, 0.05, 0.02), 1e-12));
  EXPECT_TRUE(corners[3].isApprox(Eigen::Vector3d(0.05, -0.05, 0.02), 1e-12));
}

TEST(MarkerMountTest, BadFilesAreRefusedWithTheFieldNamed) {
  const std::string pose = "pose_in_flange: {xyz: [0, 0, 0]}\n";
  auto error_of = [](const std::string& yaml) {
    auto mount = parse_marker_mount_yaml(yaml, "m.yaml");
    EXPECT_FALSE(mount) << yaml;
    return mount ? std::string() : mount.error().message;
  };
  EXPECT_EQ(error_of("id: 50\nside_m: 0.1\n" + pose),
            "m.yaml: id 50 is outside DICT_4X4_50's range 0..49");
  EXPECT_EQ(error_of("id: 1\nside_m: 0\n" + pose), "m.yaml: side_m must be positive, got 0");
  EXPECT_EQ(error_of("id: 1\nside_m: 0.1\ndictionary: DICT_6X6_250\n" + pose),
            "m.yaml: dictionary 'DICT_6X6_250' is not supported (DICT_4X4_50)");
  EXPECT_EQ(error_of("id: 1\nside_m: 0.1\n"),
            "m.yaml: pose_in_flange: missing ({xyz: [x, y, z], rpy: [r, p, y]})");
  EXPECT_EQ(error_of("id: 1\nside_m: 0.1\nsize: 2\n" + pose),
            "m.yaml: unknown key 'size' (expected dictionary, id, side_m, pose_in_flange)");
  EXPECT_EQ(error_of("id: 1\nside_m: .nan\n" + pose), "m.yaml: side_m: must be finite, got .nan");
}

TEST(MarkerMountTest, ARobotWithoutAMarkerFileIsToldWhereItWasLookedFor) {
  auto model = load_robot("puma560");
  ASSERT_TRUE(model) << model.error().message;
  RobotModel::Description d;
  d.name = "no_such_robot";
  d.joints = (*model)->joints();
  auto other = RobotModel::create(d);
  ASSERT_TRUE(other) << other.error().message;
  auto mount = marker_mount_for(*other);
  ASSERT_FALSE(mount);
  EXPECT_NE(mount.error().message.find("robot 'no_such_robot' has no marker file "
                                       "(no_such_robot.marker.yaml beside the robot's file or in "),
            std::string::npos)
      << mount.error().message;
}

}  // namespace
}  // namespace telear::core
