#include "telear/core/robot_loader.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <numbers>
#include <string>

#include "telear/core/angles.hpp"
#include "telear/core/joint_limits.hpp"
#include "telear/core/kinematics.hpp"
#include "test_util/test_util.hpp"

namespace telear::core {
namespace {

using ::testing::HasSubstr;

const char* kValidTable = R"(
name: two_link
convention: standard_dh
joints:
  - {name: a, d_m: 0.1, a_m: 0.5, alpha_deg: 0, limits_deg: [-90, 90],
     max_velocity_deg_s: 90, max_acceleration_deg_s2: 180}
  - {name: b, a_m: 0.4, alpha_rad: 0, limits_rad: [-1, 1],
     max_velocity_rad_s: 1, max_acceleration_rad_s2: 2}
named_configurations_deg:
  home: [10, 20]
)";

TEST(RobotLoader, LoadsPumaByNameWithReferenceParameters) {
  auto model = load_robot("puma560");
  ASSERT_TRUE(model) << model.error().message;
  const RobotModel& m = **model;
  EXPECT_EQ(m.name(), "puma560");
  ASSERT_EQ(m.dof(), 6);
  const std::vector<DhRow>& dh = *m.dh();
  EXPECT_DOUBLE_EQ(dh[0].d, 0.67183);
  EXPECT_DOUBLE_EQ(dh[1].a, 0.4318);
  EXPECT_DOUBLE_EQ(dh[2].d, 0.15005);
  EXPECT_DOUBLE_EQ(dh[2].a, 0.0203);
  EXPECT_DOUBLE_EQ(dh[3].d, 0.4318);
  EXPECT_NEAR(dh[0].alpha, std::numbers::pi / 2, 1e-15);
  EXPECT_NEAR(dh[2].alpha, -std::numbers::pi / 2, 1e-15);
  EXPECT_NEAR(m.upper_limits()[3], radians_from_degrees(266), 1e-15);
  EXPECT_NEAR(m.lower_limits()[4], radians_from_degrees(-100), 1e-15);
  const auto qr = m.named_configuration("qr");
  ASSERT_TRUE(qr);
  EXPECT_NEAR((*qr)[1], std::numbers::pi / 2, 1e-15);
  // qn's q3 = pi lies beyond the newer +-135 deg limit (REFERENCES.md).
  const auto violation = first_limit_violation(m, *m.named_configuration("qn"));
  ASSERT_TRUE(violation);
  EXPECT_EQ(describe_violation(m, *violation),
            "joint 3 (elbow) would be at 180.00 deg, beyond its upper limit of 135.00 deg");
}

TEST(RobotLoader, ParsesUnitsAndNamedConfigurations) {
  auto model = parse_dh_yaml(kValidTable, "inline");
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_EQ(model->dof(), 2);
  EXPECT_NEAR(model->max_velocities()[0], std::numbers::pi / 2, 1e-15);
  EXPECT_DOUBLE_EQ(model->max_accelerations()[1], 2.0);
  EXPECT_NEAR((*model->named_configuration("home"))[1], radians_from_degrees(20), 1e-15);
  EXPECT_FALSE(model->named_configuration("nope").has_value());
}

struct BadTable {
  const char* yaml;
  const char* expected;
};

class MalformedDhYaml : public ::testing::TestWithParam<BadTable> {};

TEST_P(MalformedDhYaml, IsRejectedWithAReason) {
  auto model = parse_dh_yaml(GetParam().yaml, "bad.yaml");
  ASSERT_FALSE(model);
  EXPECT_THAT(model.error().message, HasSubstr("robot file 'bad.yaml': "));
  EXPECT_THAT(model.error().message, HasSubstr(GetParam().expected));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, MalformedDhYaml,
    ::testing::Values(
        BadTable{"name: x\nconvention: standard_dh\njoints: [", "not valid YAML"},
        BadTable{"- 1\n- 2", "the file must be a YAML map"},
        BadTable{"convention: standard_dh\njoints: []", "missing 'name'"},
        BadTable{"name: x\nconvention: modified_dh\njoints: []",
                 "'convention' must be standard_dh"},
        BadTable{"name: x\nconvention: standard_dh\njoints: []",
                 "'joints' must be a non-empty list"},
        BadTable{"name: x\nconvention: standard_dh\njoints:\n  - {d_m: abc, limits_deg: [-1, 1], "
                 "max_velocity_deg_s: 1, max_acceleration_deg_s2: 1}",
                 "joints[0].d_m must be a number, got 'abc'"},
        BadTable{"name: x\nconvention: standard_dh\njoints:\n  - {d_m: .nan, limits_deg: [-1, 1], "
                 "max_velocity_deg_s: 1, max_acceleration_deg_s2: 1}",
                 "joints[0].d_m must be finite"},
        BadTable{"name: x\nconvention: standard_dh\njoints:\n  - {max_velocity_deg_s: 1, "
                 "max_acceleration_deg_s2: 1}",
                 "joints[0]: missing limits_deg or limits_rad"},
        BadTable{"name: x\nconvention: standard_dh\njoints:\n  - {limits_deg: [1, 2, 3], "
                 "max_velocity_deg_s: 1, max_acceleration_deg_s2: 1}",
                 "joints[0].limits_deg must be a list of 2 numbers"},
        BadTable{"name: x\nconvention: standard_dh\njoints:\n  - {limits_deg: [10, -10], "
                 "max_velocity_deg_s: 1, max_acceleration_deg_s2: 1}",
                 "joint 1 (joint1) has lower limit 10.00 deg above upper limit -10.00 deg"},
        BadTable{"name: x\nconvention: standard_dh\njoints:\n  - {limits_deg: [-1, 1], "
                 "max_velocity_deg_s: 0, max_acceleration_deg_s2: 1}",
                 "needs finite, positive max velocity and acceleration"},
        BadTable{"name: x\nconvention: standard_dh\njoints:\n  - {limits_deg: [-1, 1], "
                 "max_acceleration_deg_s2: 1}",
                 "missing max_velocity_deg_s"},
        BadTable{"name: x\nconvention: standard_dh\njoints:\n  - {alpha_deg: 1, alpha_rad: 1, "
                 "limits_deg: [-1, 1], max_velocity_deg_s: 1, max_acceleration_deg_s2: 1}",
                 "give alpha_deg or alpha_rad, not both"},
        BadTable{"name: x\nconvention: standard_dh\njoints:\n  - {limits_deg: [-1, 1], "
                 "max_velocity_deg_s: 1, max_acceleration_deg_s2: 1}\n"
                 "named_configurations_deg: {home: [1, 2]}",
                 "named_configurations_deg.home must be a list of 1 numbers"}),
    [](const ::testing::TestParamInfo<BadTable>& info) {
      return "case" + std::to_string(info.index);
    });

TEST(RobotLoader, ReportsMissingAndUnknownRobots) {
  auto unknown = load_robot("puma999");
  ASSERT_FALSE(unknown);
  EXPECT_THAT(unknown.error().message, HasSubstr("unknown robot 'puma999'"));
  auto missing = load_robot("/nonexistent/robot.yaml");
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().message, "robot file '/nonexistent/robot.yaml' does not exist");
  auto empty = load_robot("");
  ASSERT_FALSE(empty);
  EXPECT_THAT(empty.error().message, HasSubstr("no robot given"));
}

// data_directory()'s order (include/telear/core/robot_loader.hpp): TELEAR_DATA_DIR, then
// <program>/../share/telear/data (an installed telear; tests/install covers it), then the
// source tree's data/. A test program in the build tree has no share/ beside it.
TEST(DataDirectory, EnvironmentWinsThenTheSourceTree) {
  const char* saved = std::getenv("TELEAR_DATA_DIR");
  const std::string saved_value = saved != nullptr ? saved : "";
  ASSERT_EQ(setenv("TELEAR_DATA_DIR", "/nonexistent/telear-data", 1), 0);
  EXPECT_EQ(data_directory(), "/nonexistent/telear-data");
  auto moved = load_robot("puma560");
  ASSERT_FALSE(moved);
  EXPECT_THAT(moved.error().message, HasSubstr("no /nonexistent/telear-data/robots/puma560.yaml"));

  ASSERT_EQ(setenv("TELEAR_DATA_DIR", "", 1), 0);  // empty counts as unset
  EXPECT_EQ(data_directory(), TELEAR_TEST_DATA_DIR);
  ASSERT_EQ(unsetenv("TELEAR_DATA_DIR"), 0);
  EXPECT_EQ(data_directory(), TELEAR_TEST_DATA_DIR);
  EXPECT_TRUE(load_robot("puma560"));

  if (saved != nullptr) setenv("TELEAR_DATA_DIR", saved_value.c_str(), 1);
}

TEST(UrdfLoader, RejectsMalformedAndUnsupportedFiles) {
  auto garbage = parse_urdf("<robot name='x'><link", "g.urdf");
  ASSERT_FALSE(garbage);
  // urdfdom's own reason follows (tinyxml's wording, not ours).
  EXPECT_THAT(
      garbage.error().message,
      ::testing::StartsWith("URDF 'g.urdf': not a valid URDF (urdfdom could not parse it: "));

  const char* branching = R"(<robot name="y">
    <link name="base"/><link name="a"/><link name="b"/>
    <joint name="ja" type="revolute"><parent link="base"/><child link="a"/>
      <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
    <joint name="jb" type="revolute"><parent link="base"/><child link="b"/>
      <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  </robot>)";
  auto ambiguous = parse_urdf(branching, "y.urdf");
  ASSERT_FALSE(ambiguous);
  EXPECT_THAT(ambiguous.error().message, HasSubstr("several leaf links (a, b)"));
  auto chosen = parse_urdf(branching, "y.urdf", "b");
  ASSERT_TRUE(chosen) << chosen.error().message;
  EXPECT_EQ(chosen->joint(0).name, "jb");
  auto no_link = parse_urdf(branching, "y.urdf", "c");
  ASSERT_FALSE(no_link);
  EXPECT_EQ(no_link.error().message, "URDF 'y.urdf': has no link named 'c'");

  const char* floating = R"(<robot name="f"><link name="base"/><link name="a"/>
    <joint name="free" type="floating"><parent link="base"/><child link="a"/></joint></robot>)";
  auto f = parse_urdf(floating, "f.urdf");
  ASSERT_FALSE(f);
  EXPECT_THAT(f.error().message, HasSubstr("joint 'free' is floating or planar"));
}

TEST(UrdfLoader, HandlesArbitraryAxesPrismaticAndFixedJoints) {
  // Joint about -y, a prismatic joint along x, and a fixed tool joint.
  const char* urdf = R"(<robot name="mixed">
    <link name="base"/><link name="l1"/><link name="l2"/><link name="tip"/>
    <joint name="r" type="revolute"><parent link="base"/><child link="l1"/>
      <origin xyz="0 0 0.5" rpy="0 0 0"/><axis xyz="0 -1 0"/>
      <limit lower="-1" upper="1" effort="1" velocity="2"/></joint>
    <joint name="p" type="prismatic"><parent link="l1"/><child link="l2"/>
      <origin xyz="0.3 0 0" rpy="0 0 0"/><axis xyz="1 0 0"/>
      <limit lower="0" upper="0.2" effort="1" velocity="0.1"/></joint>
    <joint name="t" type="fixed"><parent link="l2"/><child link="tip"/>
      <origin xyz="0 0 0.1" rpy="0 0 0"/></joint>
  </robot>)";
  auto model = parse_urdf(urdf, "mixed.urdf");
  ASSERT_TRUE(model) << model.error().message;
  ASSERT_EQ(model->dof(), 2);
  EXPECT_EQ(model->joint(1).type, JointType::kPrismatic);
  EXPECT_DOUBLE_EQ(model->max_accelerations()[0], 8.0);  // 4 x velocity: URDF has none
  Eigen::VectorXd q(2);
  q << std::numbers::pi / 2, 0.1;
  // Rotating +90 deg about -y takes x to +z and z to -x.
  const Eigen::Vector3d p = tool_pose(*model, q).translation();
  const Eigen::Vector3d expected(-0.1, 0.0, 0.5 + 0.3 + 0.1);
  EXPECT_LT((p - expected).cwiseAbs().maxCoeff(), 1e-12) << p.transpose();
}

}  // namespace
}  // namespace telear::core
