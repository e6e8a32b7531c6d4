// Robot files (YAML with `urdf:`), the dispatch of load_robot_description, and the PUMA as
// before. Files are the crafted ones in tests/data/ or written by the test.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "telear/core/kinematics.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/core/robot_loader.hpp"
#include "test_util/temp_dir.hpp"
#include "test_util/test_util.hpp"

namespace telear::core {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const std::string kFiles = TELEAR_TEST_FILES_DIR;

void write(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

TEST(RobotFile, LoadsTheUrdfTipGripperConfigurationsAndMarker) {
  const std::string path = kFiles + "/robots/gripper_arm.yaml";
  auto d = load_robot_description({path, ""});
  ASSERT_TRUE(d) << d.error().message;
  EXPECT_EQ(d->name, "gripper_arm");
  EXPECT_EQ(d->model->name(), "gripper_arm");
  EXPECT_EQ(d->source, path);
  EXPECT_EQ(d->urdf_path, fs::path(kFiles + "/urdf/mimic_gripper.urdf").lexically_normal());
  EXPECT_THAT(d->urdf_text, HasSubstr("<robot name=\"mimic_gripper\">"));
  EXPECT_EQ(d->tip_link, "tcp");
  ASSERT_EQ(d->model->dof(), 2);
  // Degrees converted; `zero` replaced by the file's.
  const auto home = d->model->named_configuration("home");
  ASSERT_TRUE(home);
  EXPECT_NEAR((*home)[0], std::numbers::pi / 2, 1e-15);
  EXPECT_NEAR((*home)[1], -std::numbers::pi / 4, 1e-15);
  EXPECT_NEAR((*d->model->named_configuration("zero"))[1], 10 * std::numbers::pi / 180, 1e-15);
  EXPECT_EQ(d->model->named_configurations().size(), 2u);
  // The gripper: the driven finger, then its mimic.
  ASSERT_TRUE(d->gripper);
  ASSERT_EQ(d->gripper->joints.size(), 2u);
  EXPECT_EQ(d->gripper->joints[0].name, "finger_left");
  EXPECT_EQ(d->gripper->joints[1].name, "finger_right");
  EXPECT_EQ(d->gripper->joints[1].mimics, "finger_left");
  EXPECT_DOUBLE_EQ(d->gripper->joints[1].value(0.5), -0.02);
  EXPECT_DOUBLE_EQ(d->gripper->fraction(0.04), 0.5);
  EXPECT_DOUBLE_EQ(d->gripper->fraction(0.2), 1.0);
  EXPECT_DOUBLE_EQ(d->gripper->fraction(-1.0), 0.0);
  // The fingers open symmetrically about the hand, 0.05 below the tcp.
  std::size_t left = 0, right = 0;
  for (std::size_t i = 0; i < d->links.size(); ++i) {
    if (d->links[i].name == "left_finger") left = i;
    if (d->links[i].name == "right_finger") right = i;
  }
  EXPECT_TRUE(d->links[left].moves_with_gripper());
  EXPECT_EQ(d->links[left].frame, 2);
  const Eigen::Vector3d open_left = d->T_frame_link(left, 1.0).translation();
  const Eigen::Vector3d open_right = d->T_frame_link(right, 1.0).translation();
  EXPECT_LT((open_left - Eigen::Vector3d(0, 0.04, -0.05)).norm(), 1e-15);
  EXPECT_LT((open_right - Eigen::Vector3d(0, -0.04, -0.05)).norm(), 1e-15);
  EXPECT_LT((d->T_frame_link(left, 0.0).translation() - Eigen::Vector3d(0, 0, -0.05)).norm(),
            1e-15);
  ASSERT_TRUE(d->marker);
  EXPECT_EQ(d->marker->id, 7);
  EXPECT_DOUBLE_EQ(d->marker->side_m, 0.05);
  // --tip overrides the file's tip; load_robot(spec) gives the same chain.
  auto hand = load_robot_description({path, "hand"});
  ASSERT_TRUE(hand) << hand.error().message;
  EXPECT_EQ(hand->tip_link, "hand");
  auto model = load_robot(RobotSpec{path, ""});
  ASSERT_TRUE(model);
  EXPECT_EQ((*model)->dof(), 2);
}

TEST(RobotFile, ResolvesPackageUrisAndRelativePaths) {
  test_files::TempDir tmp("robot_file_pkg");
  const fs::path dir = tmp.path();
  std::ifstream in(kFiles + "/urdf/prismatic.urdf");
  const std::string urdf((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  write(dir / "pkgs" / "my_arm" / "urdf" / "arm.urdf", urdf);
  write(dir / "bodies" / "arm.body.yaml", "# a body\n");
  write(dir / "arm.yaml",
        "urdf: package://my_arm/urdf/arm.urdf\npackage_paths: [pkgs]\nbody: bodies/arm.body.yaml\n"
        "named_configurations_deg: {reach: [90, 0.1, 0]}\n");
  auto d = load_robot_description({(dir / "arm.yaml").string(), ""});
  ASSERT_TRUE(d) << d.error().message;
  EXPECT_EQ(d->urdf_path, (dir / "pkgs" / "my_arm" / "urdf" / "arm.urdf").string());
  EXPECT_EQ(d->package_paths, std::vector<std::string>{(dir / "pkgs").string()});
  EXPECT_EQ(d->body_file, (dir / "bodies" / "arm.body.yaml").string());
  EXPECT_EQ(d->name, "prismatic");  // no name: the URDF's
  // Degrees for the revolute joint, metres for the prismatic one.
  const auto reach = d->model->named_configuration("reach");
  ASSERT_TRUE(reach);
  EXPECT_NEAR((*reach)[0], std::numbers::pi / 2, 1e-15);
  EXPECT_DOUBLE_EQ((*reach)[1], 0.1);
  EXPECT_TRUE(d->model->named_configuration("zero"));  // kept beside the file's

  // Without package_paths, ROS_PACKAGE_PATH is searched.
  write(dir / "ros.yaml", "urdf: package://my_arm/urdf/arm.urdf\n");
  const std::string ros = (dir / "nowhere").string() + ":" + (dir / "pkgs").string();
  ASSERT_EQ(setenv("ROS_PACKAGE_PATH", ros.c_str(), 1), 0);
  auto via_ros = load_robot_description({(dir / "ros.yaml").string(), ""});
  ASSERT_EQ(unsetenv("ROS_PACKAGE_PATH"), 0);
  ASSERT_TRUE(via_ros) << via_ros.error().message;
  auto lost = load_robot_description({(dir / "ros.yaml").string(), ""});
  ASSERT_FALSE(lost);
  EXPECT_EQ(lost.error().message,
            "robot file '" + (dir / "ros.yaml").string() +
                "': urdf 'package://my_arm/urdf/arm.urdf' not found (no package search path; "
                "set ROS_PACKAGE_PATH or add a package path)");
  // --package-path (RobotSpec::package_paths) is searched too, before anything else.
  auto via_option =
      load_robot_description({(dir / "ros.yaml").string(), "", {(dir / "pkgs").string()}});
  ASSERT_TRUE(via_option) << via_option.error().message;
  EXPECT_EQ(via_option->urdf_path, via_ros->urdf_path);
}

TEST(RobotFile, ErrorsNameTheFileAndTheKey) {
  test_files::TempDir tmp("robot_file_errors");
  const fs::path dir = tmp.path();
  const std::string gripper_urdf =
      fs::path(kFiles + "/urdf/mimic_gripper.urdf").lexically_normal().string();
  struct Case {
    std::string yaml, message;
  };
  const std::vector<Case> cases = {
      {"urdf: " + gripper_urdf + "\ncolour: red\n", "unknown key 'colour'"},
      {"urdf: missing.urdf\n", "urdf: '" + (dir / "missing.urdf").string() + "' does not exist"},
      {"urdf: " + gripper_urdf + "\ntip: tcp\ngripper: {joints: [thumb], closed: [0], open: [1]}\n",
       "gripper.joints[0] 'thumb' is not a joint of URDF '" + gripper_urdf + "'"},
      {"urdf: " + gripper_urdf + "\ntip: tcp\ngripper: {joints: [j2], closed: [0], open: [1]}\n",
       "gripper.joints[0] 'j2' is on the arm's chain base -> tcp"},
      {"urdf: " + gripper_urdf +
           "\ntip: tcp\ngripper: {joints: [finger_right], closed: [0], open: [1]}\n",
       "gripper.joints[0] 'finger_right' mimics 'finger_left'; name the joint it follows"},
      {"urdf: " + gripper_urdf + "\ntip: tcp\ngripper: {joints: [finger_left], closed: [0]}\n",
       "gripper.open: missing"},
      {"urdf: " + gripper_urdf +
           "\ntip: tcp\ngripper: {joints: [finger_left], closed: [0], open: [1], "
           "max_opening_m: 0}\n",
       "gripper.max_opening_m must be positive"},
      {"urdf: " + gripper_urdf + "\ntip: tcp\nnamed_configurations_deg: {home: [1, 2, 3]}\n",
       "named_configurations_deg.home must be a list of 2 numbers (one per chain joint)"},
      {"urdf: " + gripper_urdf + "\ntip: tcp\nbody: nobody.yaml\n",
       "body: '" + (dir / "nobody.yaml").string() + "' does not exist"},
      {"urdf: " + gripper_urdf + "\ntip: tcp\nmarker: {id: 99, side_m: 0.1}\n", "marker: id"},
      {"urdf: [a, b]\n", "urdf must be a non-empty string"},
      {"urdf: " + gripper_urdf + "\ntip: tcp\nallowed_collisions: [[base, elbow, never]]\n",
       "allowed_collisions[0]: 'elbow' is not a link of the URDF"},
      {"urdf: " + gripper_urdf + "\ntip: tcp\nallowed_collisions: [[base, l1, sometimes]]\n",
       "allowed_collisions[0]: unknown reason 'sometimes' (adjacent, always, never, constant or "
       "user)"},
      {"urdf: " + gripper_urdf + "\ntip: tcp\nallowed_collisions: [[base]]\n",
       "allowed_collisions[0]: must be [link, link] or [link, link, reason]"},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const fs::path path = dir / ("case" + std::to_string(i) + ".yaml");
    write(path, cases[i].yaml);
    auto d = load_robot_description({path.string(), ""});
    ASSERT_FALSE(d) << cases[i].yaml;
    EXPECT_THAT(d.error().message, HasSubstr("robot file '" + path.string() + "': "));
    EXPECT_THAT(d.error().message, HasSubstr(cases[i].message));
  }
}

// The allowed-collision matrix stored in the robot file (geometry/allowed_collisions.hpp).
TEST(RobotFile, KeepsTheAllowedCollisionPairs) {
  test_files::TempDir tmp("robot_file_acm");
  const fs::path dir = tmp.path();
  const std::string gripper_urdf =
      fs::path(kFiles + "/urdf/mimic_gripper.urdf").lexically_normal().string();
  write(dir / "acm.yaml", "urdf: " + gripper_urdf +
                              "\ntip: tcp\nallowed_collisions:\n  - [base, hand, never]\n"
                              "  - [left_finger, l1]\n");
  auto d = load_robot_description({(dir / "acm.yaml").string(), "", {}});
  ASSERT_TRUE(d) << d.error().message;
  ASSERT_TRUE(d->allowed_collisions);
  ASSERT_EQ(d->allowed_collisions->size(), 2u);
  EXPECT_EQ((*d->allowed_collisions)[0].b, "hand");
  EXPECT_EQ((*d->allowed_collisions)[0].reason, "never");
  EXPECT_EQ((*d->allowed_collisions)[1].reason, "user");
  // None stored: unset (the geometry layer computes one).
  write(dir / "none.yaml", "urdf: " + gripper_urdf + "\ntip: tcp\n");
  auto none = load_robot_description({(dir / "none.yaml").string(), "", {}});
  ASSERT_TRUE(none) << none.error().message;
  EXPECT_FALSE(none->allowed_collisions);
  // The shipped URDF arms store theirs (`telear robot acm`; tests/geometry checks it).
  auto shipped = load_robot_description({"ur6", "", {}});
  ASSERT_TRUE(shipped) << shipped.error().message;
  ASSERT_TRUE(shipped->allowed_collisions);
  EXPECT_FALSE(shipped->allowed_collisions->empty());
}

// A robot server's GetInfo URDF, as text (a recorder names /tf's frames by its links).
TEST(RobotDescription, AUrdfTextParsesWithItsLinksByName) {
  auto puma = load_robot_description({"puma560"});
  ASSERT_TRUE(puma) << puma.error().message;
  const std::string urdf = urdf_text_for_clients(*puma);
  auto parsed = parse_urdf_description(urdf, "the server's URDF");
  ASSERT_TRUE(parsed) << parsed.error().message;
  EXPECT_EQ(parsed->model->dof(), 6);
  EXPECT_EQ(parsed->source, "the server's URDF");
  EXPECT_EQ(parsed->urdf_text, urdf);
  EXPECT_FALSE(parsed->root_link.empty());
  EXPECT_NE(parsed->link("link6"), nullptr);
  EXPECT_FALSE(parsed->marker);  // no companion files
  auto bad = parse_urdf_description("<robot name='x'><link name='a'/>", "the server's URDF");
  ASSERT_FALSE(bad);
  EXPECT_THAT(bad.error().message, HasSubstr("the server's URDF"));
}

TEST(RobotDescription, ThePumaLoadsAsBefore) {
  auto dh = load_robot_description({"puma560", ""});
  ASSERT_TRUE(dh) << dh.error().message;
  EXPECT_TRUE(dh->links.empty());
  EXPECT_TRUE(dh->urdf_text.empty());
  ASSERT_TRUE(dh->model->dh());
  EXPECT_TRUE(dh->marker);  // puma560.marker.yaml
  EXPECT_THAT(dh->body_file, HasSubstr("puma560.body.yaml"));
  auto tip = load_robot_description({"puma560", "flange"});
  ASSERT_FALSE(tip);
  EXPECT_THAT(tip.error().message, HasSubstr("is a DH table: it has no links"));

  auto urdf = load_robot_description({test::data_path("robots/puma560.urdf"), ""});
  ASSERT_TRUE(urdf) << urdf.error().message;
  EXPECT_EQ(urdf->model->dof(), 6);
  EXPECT_EQ(urdf->root_link, "base_link");
  EXPECT_EQ(urdf->links.size(), 8u);
  std::mt19937_64 rng(7);
  for (int k = 0; k < 100; ++k) {
    const Eigen::VectorXd q = test::random_configuration(*dh->model, rng);
    EXPECT_LT(
        test::max_abs_diff(tool_pose(*dh->model, q).matrix(), tool_pose(*urdf->model, q).matrix()),
        1e-12);
  }
  auto old = load_robot("puma560");
  ASSERT_TRUE(old);
  EXPECT_TRUE((*old)->dh());
}

}  // namespace
}  // namespace telear::core
