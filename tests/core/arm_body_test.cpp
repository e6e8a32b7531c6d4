// The arm body (no GL): primitive counts and winding, the body file, the default body for a
// robot without one, and the per-link pose with its changed-part range.

#include "telear/core/arm_body.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "telear/core/arm_body_pose.hpp"
#include "telear/core/robot_loader.hpp"
#include "test_util/test_util.hpp"

namespace telear::core {
namespace {

using ::testing::HasSubstr;

Eigen::Vector3f position(const Mesh& m, std::uint32_t i) {
  const MeshVertex& v = m.vertices[i];
  return {v.position[0], v.position[1], v.position[2]};
}

// Every triangle's geometric normal (from its winding) points away from `centre`: the mesh
// is wound counter-clockwise seen from outside.
void expect_outward_winding(const Mesh& m, const Eigen::Vector3f& centre) {
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    const Eigen::Vector3f a = position(m, m.triangles[3 * t]);
    const Eigen::Vector3f b = position(m, m.triangles[3 * t + 1]);
    const Eigen::Vector3f c = position(m, m.triangles[3 * t + 2]);
    const Eigen::Vector3f n = (b - a).cross(c - a);
    const Eigen::Vector3f mid = (a + b + c) / 3.0f;
    EXPECT_GT(n.dot(mid - centre), 0.0f) << "triangle " << t << " is wound inwards";
  }
}

TEST(MeshTest, StripAndFanExpandToTrianglesKeepingTheWinding) {
  Mesh m;
  m.append_triangle_strip({0, 1, 2, 3, 4});
  EXPECT_EQ(m.triangles, (std::vector<std::uint32_t>{0, 1, 2, 2, 1, 3, 2, 3, 4}));
  Mesh f;
  f.append_triangle_fan({0, 1, 2, 3});
  EXPECT_EQ(f.triangles, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));
}

TEST(MeshTest, CylinderCountsFollowTheFormulaForEverySegmentCount) {
  for (int n : {3, 8, 16, 50}) {
    Mesh m;
    append_cylinder(m, {0, 0, 0}, {0, 0, 1}, 0.1f, n, {1, 1, 1});
    EXPECT_EQ(static_cast<int>(m.triangle_count()), cylinder_triangle_count(n)) << n;
    EXPECT_EQ(static_cast<int>(m.triangle_count()), 4 * n) << n;
    EXPECT_EQ(static_cast<int>(m.line_count()), cylinder_line_count(n)) << n;
    // Wall: 2 (N + 1); caps: 2 (N + 1).
    EXPECT_EQ(m.vertices.size(), static_cast<std::size_t>(4 * (n + 1))) << n;
  }
}

TEST(MeshTest, CylinderIsClosedWoundOutwardsWithUnitNormals) {
  Mesh m;
  const Eigen::Vector3f p0(0.1f, -0.2f, 0.3f), p1(0.4f, 0.2f, 0.1f);
  append_cylinder(m, p0, p1, 0.05f, 12, {1, 0, 0});
  expect_outward_winding(m, (p0 + p1) / 2);
  const Eigen::Vector3f axis = (p1 - p0).normalized();
  for (const MeshVertex& v : m.vertices) {
    const Eigen::Vector3f n(v.normal[0], v.normal[1], v.normal[2]);
    EXPECT_NEAR(n.norm(), 1.0f, 1e-5f);
    const Eigen::Vector3f p = Eigen::Vector3f(v.position[0], v.position[1], v.position[2]) - p0;
    const float radial = (p - p.dot(axis) * axis).norm();
    EXPECT_LE(radial, 0.05f + 1e-5f);
  }
}

TEST(MeshTest, TaperedBoxHasTwelveOutwardTrianglesAndTwelveEdges) {
  Mesh m;
  append_tapered_box(m, {0, 0, 0}, {1, 0, 0}, {0.4f, 0.2f}, {0.2f, 0.1f}, {0, 0, 1}, {1, 1, 1});
  EXPECT_EQ(static_cast<int>(m.triangle_count()), kBoxTriangleCount);
  EXPECT_EQ(static_cast<int>(m.line_count()), kBoxLineCount);
  expect_outward_winding(m, {0.5f, 0, 0});
  // Every edge joins two corners that differ in exactly... the lines have non-zero length.
  for (std::size_t k = 0; k < m.line_count(); ++k) {
    EXPECT_GT((position(m, m.lines[2 * k]) - position(m, m.lines[2 * k + 1])).norm(), 0.05f);
  }
}

class ArmBodyTest : public ::testing::Test {
 protected:
  void SetUp() override {
    model = test::puma560();
    ASSERT_TRUE(model);
    auto d = body_description_for(*model);
    ASSERT_TRUE(d) << d.error().message;
    description = *d;
  }
  RobotModelPtr model;
  BodyDescription description;
};

TEST_F(ArmBodyTest, ThePumaShipsABodyFileWithAGripperAndPrisms) {
  EXPECT_THAT(description.source, HasSubstr("puma560.body.yaml"));
  ASSERT_EQ(description.links.size(), 7u);
  ASSERT_TRUE(description.gripper);
  EXPECT_EQ(description.gripper->link, 6);
  EXPECT_EQ(description.links[2][0].kind, ShapeSpec::Kind::kPrism);  // upper arm
  EXPECT_EQ(description.links[3][0].kind, ShapeSpec::Kind::kPrism);  // forearm
  const ArmBody body = build_arm_body(description);
  ASSERT_EQ(body.part_count(), 9);  // base, 6 links, 2 fingers
  for (int i = 0; i <= 6; ++i) {
    EXPECT_EQ(body.parts[static_cast<std::size_t>(i)].link, i);
    EXPECT_GT(body.parts[static_cast<std::size_t>(i)].mesh.triangle_count(), 0u) << i;
  }
  EXPECT_EQ(body.parts[7].finger_side, -1);
  EXPECT_EQ(body.parts[8].finger_side, +1);
}

TEST_F(ArmBodyTest, SegmentCountChangesTheTriangleCountByTheFormula) {
  int cylinders = 0;
  for (const auto& link : description.links) {
    for (const ShapeSpec& s : link) cylinders += s.kind == ShapeSpec::Kind::kCylinder;
  }
  ASSERT_GT(cylinders, 0);
  const ArmBody b8 = build_arm_body(description, {.segments_override = 8});
  const ArmBody b50 = build_arm_body(description, {.segments_override = 50});
  EXPECT_EQ(
      static_cast<long>(b50.triangle_count()) - static_cast<long>(b8.triangle_count()),
      static_cast<long>(cylinders) * (cylinder_triangle_count(50) - cylinder_triangle_count(8)));
  EXPECT_EQ(static_cast<long>(b50.line_count()) - static_cast<long>(b8.line_count()),
            static_cast<long>(cylinders) * (cylinder_line_count(50) - cylinder_line_count(8)));
}

TEST_F(ArmBodyTest, FingerInnerFacesAreTheOpeningApartAndClamped) {
  const GripperSpec& g = *description.gripper;
  const float half = g.finger_size.dot(g.axis) / 2;
  for (float w : {0.0f, 0.03f, 0.08f}) {
    const Eigen::Vector3f left = T_link_finger(g, -1, w).translation();
    const Eigen::Vector3f right = T_link_finger(g, +1, w).translation();
    EXPECT_NEAR((right - left).dot(g.axis) - 2 * half, w, 1e-6f);
  }
  const float too_wide =
      (T_link_finger(g, +1, 1.0f).translation() - T_link_finger(g, -1, 1.0f).translation())
          .dot(g.axis);
  EXPECT_NEAR(too_wide - 2 * half, g.max_opening, 1e-6f);
}

TEST_F(ArmBodyTest, MovingJointFiveChangesTheMatricesOfLinksFiveAndSixOnly) {
  const ArmBody body = build_arm_body(description);
  ArmBodyPose pose(*model, body);
  EXPECT_EQ(pose.changed().first, 0);
  EXPECT_EQ(pose.changed().count, body.part_count());  // all new
  pose.clear_changes();
  const std::vector<Eigen::Matrix4f> before = pose.T_base_part();

  pose.set_joint(4, 0.7);  // joint 5 (1-based)
  const PartRange r = pose.changed();
  EXPECT_EQ(r.first, 5);
  EXPECT_EQ(r.count, 4);  // links 5, 6 and the two fingers riding on link 6
  for (int k = 0; k < body.part_count(); ++k) {
    const bool same = pose.T_base_part(k) == before[static_cast<std::size_t>(k)];
    const bool moves = body.parts[static_cast<std::size_t>(k)].link >= 5;
    EXPECT_EQ(same, !moves) << "part " << k << " (" << body.parts[static_cast<std::size_t>(k)].name
                            << ")";
  }
  // Frames 0..4 were not even re-computed.
  EXPECT_EQ(pose.kinematics().last_first_updated_joint, 4);
  EXPECT_EQ(pose.kinematics().last_frames_recomputed, 2);

  // The matrices are the link frames.
  for (int k = 0; k <= 6; ++k) {
    EXPECT_TRUE(pose.T_base_part(k).isApprox(
        pose.kinematics().T_base_link[static_cast<std::size_t>(k)].matrix().cast<float>(), 1e-6f));
  }
}

TEST_F(ArmBodyTest, ChangesAccumulateUntilClearedAndOpeningMovesOnlyFingers) {
  const ArmBody body = build_arm_body(description);
  ArmBodyPose pose(*model, body);
  pose.clear_changes();
  pose.set_gripper_opening(0.07f);
  EXPECT_EQ(pose.changed().first, 7);
  EXPECT_EQ(pose.changed().count, 2);
  pose.set_joint(5, 0.2);  // joint 6: link 6 and the fingers
  EXPECT_EQ(pose.changed().first, 6);
  EXPECT_EQ(pose.changed().count, 3);
  pose.clear_changes();
  Eigen::VectorXd q = pose.q();
  pose.set_configuration(q);  // nothing differs
  EXPECT_TRUE(pose.changed().empty());
  q[1] += 0.1;  // joint 2: links 2..6 and the fingers
  pose.set_configuration(q);
  EXPECT_EQ(pose.changed().first, 2);
  EXPECT_EQ(pose.changed().count, 7);
  pose.clear_changes();
  pose.set_gripper_opening(0.5f);  // clamped to the maximum
  EXPECT_FLOAT_EQ(pose.gripper_opening(), description.gripper->max_opening);
}

TEST(DefaultBodyTest, ARobotWithoutABodyFileGetsCylindersAlongItsLinks) {
  // The URDF PUMA has other link frames than the DH body file: it gets the default body.
  auto urdf = load_robot(test::data_path("robots/puma560.urdf"));
  ASSERT_TRUE(urdf) << urdf.error().message;
  auto d = body_description_for(**urdf);
  ASSERT_TRUE(d) << d.error().message;
  EXPECT_EQ(d->source, "default");
  EXPECT_FALSE(d->gripper);
  const ArmBody body = build_arm_body(*d);
  EXPECT_EQ(body.part_count(), 7);
  // Every joint has its axis cylinder; links with offsets have link cylinders.
  for (const auto& link : d->links) {
    for (const ShapeSpec& s : link) EXPECT_EQ(s.kind, ShapeSpec::Kind::kCylinder);
  }
  EXPECT_GT(body.triangle_count(), 0u);

  // The DH model's default body puts a cylinder along d1 (0.67 m) in link 1.
  auto dh = test::puma560();
  const BodyDescription dd = default_body_description(*dh);
  float longest = 0;
  for (const ShapeSpec& s : dd.links[1]) longest = std::max(longest, (s.to - s.from).norm());
  EXPECT_NEAR(longest, 0.67183f, 1e-5f);
}

struct BadBody {
  const char* text;
  const char* message;
};

class BodyFileErrorTest : public ::testing::TestWithParam<BadBody> {};

TEST_P(BodyFileErrorTest, NamesTheProblem) {
  auto model = test::puma560();
  auto d = parse_body_yaml(GetParam().text, "bad.body.yaml", *model);
  ASSERT_FALSE(d);
  EXPECT_THAT(d.error().message, HasSubstr("body file 'bad.body.yaml'"));
  EXPECT_THAT(d.error().message, HasSubstr(GetParam().message));
}

INSTANTIATE_TEST_SUITE_P(
    Errors, BodyFileErrorTest,
    ::testing::Values(
        BadBody{"[1, 2]", "must be a YAML map"},
        BadBody{"links: {1: [{type: cylinder, from_m: [0,0,0], to_m: [0,0,1]}]}",
                "links.1[0].radius_m must be a number"},
        BadBody{"links: {7: []}", "'7' is not a link index in [0, 6]"},
        BadBody{"links: {1: [{type: cone}]}", "unknown type 'cone'"},
        BadBody{"links: {1: [{type: box, centre_m: [0,0,0], size_m: [1,1,1], colour: [2,0,0]}]}",
                "colour must be RGB values in [0, 1]"},
        BadBody{"links: {1: [{type: cylinder, from_m: [0,0,0], to_m: [0,0,1], radius_m: 0.1, "
                "segments: 2}]}",
                "segments must be a whole number in [3, 1024]"},
        BadBody{"links: {1: [{type: cylinder, from_m: [0,0,0], to_m: [0,0,1], radus_m: 0.1}]}",
                "unknown key 'radus_m'"},
        BadBody{"links: {1: [{type: prism, from_m: [0,0,0], to_m: [0,0,1], size_from_m: [1,1], "
                "up: [0,0,2]}]}",
                "'up' must not be parallel"},
        BadBody{"robot: ur5\nlinks: {}", "describes robot 'ur5', not 'puma560'"},
        BadBody{"links: {}\ngripper: {link: 9}", "gripper.link must be a link index in [1, 6]"},
        BadBody{"links: {1: [", "not valid YAML"}));

TEST(BodyFileTest, AMissingFileIsAnError) {
  auto model = test::puma560();
  auto d = load_body_yaml_file("/nonexistent/x.body.yaml", *model);
  ASSERT_FALSE(d);
  EXPECT_THAT(d.error().message, HasSubstr("cannot open body file '/nonexistent/x.body.yaml'"));
}

// A URDF-style body on the PUMA's chain: a prebuilt mesh appended to link 6 and two moving
// fingers driven by one revolute gripper joint and its mimic (multiplier -1).
TEST_F(ArmBodyTest, MovingPartsFollowTheGripperJointsAndOnlyTheirMatricesChange) {
  BodyDescription d;
  d.links.resize(7);
  d.link_meshes.resize(7);
  append_box(d.link_meshes[6], Eigen::Vector3f::Zero(), {0.05f, 0.05f, 0.05f}, {1, 1, 1});
  GripperJoint driven;
  driven.type = JointType::kRevolute;
  driven.before.translation() = Eigen::Vector3d(0, 0, 0.1);
  driven.closed = 0.0;
  driven.open = 0.5;
  GripperJoint mimic = driven;
  mimic.multiplier = -1.0;
  mimic.mimics = "driven";
  d.gripper_joints = Gripper{{driven, mimic}, 0.1};
  for (int k : {0, 1}) {
    MovingPartSpec part;
    part.name = k == 0 ? "left" : "right";
    part.link = 6;
    AttachmentStep step;
    step.gripper_joint = k;
    AttachmentStep tip;
    tip.fixed.translation() = Eigen::Vector3d(0.05, 0, 0);
    part.steps = {step, tip};
    append_box(part.mesh, Eigen::Vector3f::Zero(), {0.01f, 0.01f, 0.04f}, {1, 0, 0});
    d.moving_parts.push_back(part);
  }
  const ArmBody body = build_arm_body(d);
  ASSERT_EQ(body.part_count(), 9);
  EXPECT_EQ(body.parts[6].mesh.triangle_count(), static_cast<std::size_t>(kBoxTriangleCount));
  EXPECT_TRUE(body.has_gripper());
  EXPECT_FLOAT_EQ(body.max_gripper_opening(), 0.1f);

  ArmBodyPose pose(*model, body);
  pose.clear_changes();
  pose.set_gripper_opening(0.1f);  // fraction 1: the joints at +0.5 and -0.5 rad
  EXPECT_EQ(pose.changed().first, 7);
  EXPECT_EQ(pose.changed().count, 2);
  const Eigen::Matrix4f T6 = pose.kinematics().T_base_link[6].matrix().cast<float>();
  for (int k : {0, 1}) {
    const double angle = k == 0 ? 0.5 : -0.5;
    const Eigen::Isometry3d expected = Eigen::Translation3d(0, 0, 0.1) *
                                       Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()) *
                                       Eigen::Translation3d(0.05, 0, 0);
    EXPECT_TRUE(pose.T_base_part(7 + k).isApprox(T6 * expected.matrix().cast<float>(), 1e-5f)) << k;
    EXPECT_TRUE(body.T_link_part(7 + k, 0.1f).isApprox(expected.cast<float>(), 1e-5f)) << k;
  }
  pose.clear_changes();
  pose.set_gripper_opening(0.2f);  // clamped to the maximum it is already at: nothing moves
  EXPECT_TRUE(pose.changed().empty());
}

}  // namespace
}  // namespace telear::core
