// The URDF conformance set (tests/data/urdf/): one small crafted URDF per feature, each loaded
// and checked against transforms written out by hand from the file's numbers, and hostile
// ones, each refused with a message naming the file, the element and the reason.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "telear/core/kinematics.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/core/robot_loader.hpp"

namespace telear::core {
namespace {

using ::testing::HasSubstr;

std::string urdf(const std::string& name) {
  return std::string(TELEAR_TEST_FILES_DIR) + "/urdf/" + name + ".urdf";
}

RobotDescription load(const std::string& name, const std::string& tip = "") {
  auto d = load_robot_description({urdf(name), tip});
  EXPECT_TRUE(d) << d.error().message;
  return d ? std::move(d).value() : RobotDescription{};
}

std::string refusal(const std::string& name, const std::string& tip = "") {
  auto d = load_robot_description({urdf(name), tip});
  EXPECT_FALSE(d) << name << " loaded";
  return d ? std::string() : d.error().message;
}

Eigen::Isometry3d xyz_rpy(double x, double y, double z, double r, double p, double yaw) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(x, y, z);
  T.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(p, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(r, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  return T;
}

Eigen::Isometry3d rot(const Eigen::Vector3d& axis, double angle) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  return T;
}

double diff(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.matrix() - b.matrix()).cwiseAbs().maxCoeff();
}

std::size_t index_of(const RobotDescription& d, const std::string& link) {
  for (std::size_t i = 0; i < d.links.size(); ++i) {
    if (d.links[i].name == link) return i;
  }
  ADD_FAILURE() << "no link " << link;
  return 0;
}

TEST(UrdfConformance, BranchingTreeNeedsATipAndListsTheLeaves) {
  EXPECT_EQ(refusal("branching_tip"),
            "URDF '" + urdf("branching_tip") +
                "': the tree has several leaf links (a, b, tcp); name the tip link");
  EXPECT_EQ(refusal("branching_tip", "nope"),
            "URDF '" + urdf("branching_tip") + "': has no link named 'nope'");
  const RobotDescription d = load("branching_tip", "a");
  ASSERT_TRUE(d.model);
  EXPECT_EQ(d.root_link, "base");
  EXPECT_EQ(d.tip_link, "a");
  ASSERT_EQ(d.model->dof(), 2);
  EXPECT_EQ(d.model->joint(1).name, "ja");
  ASSERT_EQ(d.links.size(), 5u);  // every link, on the chain or not
  // b hangs from l1 (frame 1) through jb, held at 0; tcp through the fixed jt.
  const RobotLink* b = d.link("b");
  ASSERT_NE(b, nullptr);
  EXPECT_EQ(b->frame, 1);
  EXPECT_FALSE(b->moves_with_gripper());
  EXPECT_LT(diff(d.T_frame_link(index_of(d, "b"), 0.0), xyz_rpy(-0.2, 0, 0, 0, 0, 0)), 1e-15);
  EXPECT_EQ(d.link("tcp")->frame, 1);
  EXPECT_LT(diff(d.T_frame_link(index_of(d, "tcp"), 0.0), xyz_rpy(0, 0, 0.1, 0, 0, 0)), 1e-15);
  EXPECT_EQ(d.link("a")->frame, 2);
  EXPECT_TRUE(d.link("a")->steps.empty());
  EXPECT_EQ(d.link("nope"), nullptr);
  // Tip b instead: another chain from the same file.
  EXPECT_EQ(load("branching_tip", "b").model->joint(1).name, "jb");
}

TEST(UrdfConformance, WorldRootIsFrameZero) {
  const RobotDescription d = load("world_root");
  ASSERT_TRUE(d.model);
  EXPECT_EQ(d.root_link, "world");
  EXPECT_EQ(d.tip_link, "tool0");
  ASSERT_EQ(d.model->dof(), 2);
  const Eigen::Isometry3d world_base = xyz_rpy(0.1, 0.2, 0.5, 0, 0, std::numbers::pi / 2);
  EXPECT_EQ(d.link("base_link")->frame, 0);
  EXPECT_LT(diff(d.T_frame_link(index_of(d, "base_link"), 0), world_base), 1e-15);
  const Eigen::VectorXd q = Eigen::Vector2d(0.4, -0.7);
  const Eigen::Isometry3d expected =
      world_base * xyz_rpy(0, 0, 0.2, 0, 0, 0) * rot(Eigen::Vector3d::UnitZ(), q[0]) *
      xyz_rpy(0, 0, 0.4, 0, 0.3, 0) * rot(Eigen::Vector3d::UnitY(), q[1]) *
      xyz_rpy(0.3, 0, 0, 0, std::numbers::pi / 2, 0);
  EXPECT_LT(diff(tool_pose(*d.model, q), expected), 1e-12);
  // l2 rides on frame 2 (tool0) behind the fixed flange joint.
  EXPECT_EQ(d.link("l2")->frame, 2);
  EXPECT_LT(diff(d.T_frame_link(index_of(d, "l2"), 0),
                 xyz_rpy(0.3, 0, 0, 0, std::numbers::pi / 2, 0).inverse()),
            1e-15);
}

TEST(UrdfConformance, FixedJointsFoldIntoTheChain) {
  const RobotDescription d = load("fixed_chain");
  ASSERT_TRUE(d.model);
  ASSERT_EQ(d.model->dof(), 2);
  // Frame 1 is l1b (the last link before j2), frame 2 is tool0.
  EXPECT_EQ(d.link("l1b")->frame, 1);
  EXPECT_TRUE(d.link("l1b")->steps.empty());
  EXPECT_EQ(d.link("l1")->frame, 1);
  EXPECT_LT(diff(d.T_frame_link(index_of(d, "l1"), 0), xyz_rpy(0.1, 0, 0.05, 0.5, 0, 0).inverse()),
            1e-15);
  EXPECT_EQ(d.link("flange")->frame, 2);
  EXPECT_LT(
      diff(d.T_frame_link(index_of(d, "flange"), 0), xyz_rpy(0, 0, 0.05, 0, 0, 0.7).inverse()),
      1e-15);
  KinematicsData data(*d.model);
  const Eigen::VectorXd q = Eigen::Vector2d(1.1, 0.3);
  forward_kinematics(*d.model, data, q);
  const Eigen::Isometry3d l1b = xyz_rpy(0, 0, 0.25, 0, 0, 0) * rot(Eigen::Vector3d::UnitZ(), q[0]) *
                                xyz_rpy(0.1, 0, 0.05, 0.5, 0, 0);
  EXPECT_LT(diff(data.T_base_link[1], l1b), 1e-12);
  const Eigen::Isometry3d tool0 = l1b * xyz_rpy(0, 0, 0.3, 0, 0, 0) *
                                  rot(Eigen::Vector3d::UnitX(), q[1]) *
                                  xyz_rpy(0, 0.2, 0, 0, 0, 0) * xyz_rpy(0, 0, 0.05, 0, 0, 0.7);
  EXPECT_LT(diff(data.T_base_link[2], tool0), 1e-12);
}

TEST(UrdfConformance, ContinuousJointsHaveInfiniteLimitsAndDefaultVelocity) {
  const RobotDescription d = load("continuous");
  ASSERT_TRUE(d.model);
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(d.model->lower_limits()[0], -inf);
  EXPECT_EQ(d.model->upper_limits()[1], inf);
  EXPECT_DOUBLE_EQ(d.model->max_velocities()[0], 3.0);     // <limit velocity="3">
  EXPECT_DOUBLE_EQ(d.model->max_velocities()[1], 1.0);     // no <limit>: the default
  EXPECT_DOUBLE_EQ(d.model->max_accelerations()[1], 4.0);  // 4 x velocity
  // The wrist axis (0, 0.6, 0.8) is normalised.
  const Eigen::VectorXd q = Eigen::Vector2d(0, 5.0);
  const Eigen::Isometry3d expected = xyz_rpy(0, 0, 0.2, 0, 0, 0) * xyz_rpy(0.1, 0, 0.1, 0, 0, 0) *
                                     rot(Eigen::Vector3d(0, 0.6, 0.8), 5.0);
  EXPECT_LT(diff(tool_pose(*d.model, q), expected), 1e-12);
}

TEST(UrdfConformance, PrismaticJointsSlideAlongTheirAxis) {
  const RobotDescription d = load("prismatic");
  ASSERT_TRUE(d.model);
  ASSERT_EQ(d.model->dof(), 3);
  EXPECT_EQ(d.model->joint(1).type, JointType::kPrismatic);
  EXPECT_DOUBLE_EQ(d.model->upper_limits()[1], 0.3);
  EXPECT_DOUBLE_EQ(d.model->max_velocities()[1], 0.25);
  const Eigen::VectorXd q = Eigen::Vector3d(0.5, 0.12, -0.3);
  const Eigen::Isometry3d expected =
      xyz_rpy(0, 0, 0.1, 0, 0, 0) * rot(Eigen::Vector3d::UnitZ(), q[0]) *
      xyz_rpy(0.2 + q[1], 0, 0, 0, 0, 0) * xyz_rpy(0, 0, 0.05, 0, 0, 0) *
      rot(-Eigen::Vector3d::UnitY(), q[2]);
  EXPECT_LT(diff(tool_pose(*d.model, q), expected), 1e-12);
}

TEST(UrdfConformance, MissingVelocityLimitsTakeTheDocumentedDefault) {
  const RobotDescription d = load("no_velocity");
  ASSERT_TRUE(d.model);
  EXPECT_DOUBLE_EQ(d.model->max_velocities()[0], 1.0);  // velocity="0"
  EXPECT_DOUBLE_EQ(d.model->max_velocities()[1], 1.0);  // no <limit>
  EXPECT_DOUBLE_EQ(d.model->lower_limits()[0], -1.0);
}

TEST(UrdfConformance, GripperJointsAreHeldWithoutARobotFile) {
  const RobotDescription d = load("mimic_gripper", "tcp");
  ASSERT_TRUE(d.model);
  EXPECT_EQ(d.model->dof(), 2);
  EXPECT_FALSE(d.gripper);
  const RobotLink* right = d.link("right_finger");
  ASSERT_NE(right, nullptr);
  EXPECT_EQ(right->frame, 2);
  EXPECT_FALSE(right->moves_with_gripper());
  // hand -> tcp is 0.1 along z, the fingers sit 0.05 along z: 0.05 below the tip frame.
  EXPECT_LT(diff(d.T_frame_link(index_of(d, "right_finger"), 1.0), xyz_rpy(0, 0, -0.05, 0, 0, 0)),
            1e-15);
}

TEST(UrdfConformance, MeshesKeepTheirUrisScalesAndOrigins) {
  const RobotDescription d = load("meshes");
  const RobotLink* base = d.link("base");
  ASSERT_NE(base, nullptr);
  ASSERT_EQ(base->visuals.size(), 1u);
  const GeometryElement& mesh = base->visuals[0];
  EXPECT_EQ(mesh.kind, GeometryElement::Kind::kMesh);
  EXPECT_EQ(mesh.mesh_uri, "package://telear_test_pkg/meshes/base.stl");
  EXPECT_EQ(mesh.scale, Eigen::Vector3d(0.001, 0.001, 0.002));
  EXPECT_LT(diff(mesh.T_link_geometry, xyz_rpy(0, 0, 0.05, 0, 0, 0.5)), 1e-15);
  ASSERT_EQ(base->collisions.size(), 1u);
  EXPECT_EQ(base->collisions[0].kind, GeometryElement::Kind::kCylinder);
  EXPECT_DOUBLE_EQ(base->collisions[0].radius, 0.1);
  EXPECT_DOUBLE_EQ(base->collisions[0].length, 0.2);
  const RobotLink* l1 = d.link("l1");
  ASSERT_NE(l1, nullptr);
  ASSERT_EQ(l1->visuals.size(), 2u);
  EXPECT_EQ(l1->visuals[0].mesh_uri, "meshes/l1.obj");  // relative, unresolved
  EXPECT_EQ(l1->visuals[0].scale, Eigen::Vector3d::Ones());
  EXPECT_EQ(l1->visuals[1].kind, GeometryElement::Kind::kSphere);
  EXPECT_DOUBLE_EQ(l1->visuals[1].radius, 0.03);
  ASSERT_EQ(l1->collisions.size(), 1u);
  EXPECT_EQ(l1->collisions[0].kind, GeometryElement::Kind::kBox);
  EXPECT_EQ(l1->collisions[0].box_size, Eigen::Vector3d(0.1, 0.2, 0.3));
  EXPECT_FALSE(l1->visuals[0].rgba);
}

TEST(UrdfConformance, MaterialsComeFromTheLinkOrTheModel) {
  const RobotDescription d = load("materials");
  ASSERT_EQ(d.link("base")->visuals.size(), 1u);
  const GeometryElement& box = d.link("base")->visuals[0];
  EXPECT_EQ(box.material_name, "orange");
  ASSERT_TRUE(box.rgba);
  EXPECT_EQ(*box.rgba, Eigen::Vector4f(1.0f, 0.5f, 0.0f, 1.0f));
  ASSERT_EQ(d.link("l1")->visuals.size(), 2u);
  ASSERT_TRUE(d.link("l1")->visuals[0].rgba);
  EXPECT_EQ(*d.link("l1")->visuals[0].rgba, Eigen::Vector4f(0.0f, 0.0f, 1.0f, 0.5f));
  EXPECT_FALSE(d.link("l1")->visuals[1].rgba);
}

TEST(UrdfConformance, HostileFilesAreRefusedWithWhatAndWhere) {
  const auto where = [](const std::string& name) { return "URDF '" + urdf(name) + "': "; };
  EXPECT_EQ(refusal("cycle"),
            where("cycle") +
                "link 'a' is the child of several joints (j0, j2); a URDF must be a tree (is "
                "there a cycle?)");
  const std::string missing = refusal("missing_parent");
  EXPECT_THAT(missing, HasSubstr(where("missing_parent") + "not a valid URDF"));
  EXPECT_THAT(missing, HasSubstr("parent link [ghost] of joint [j1] not found"));
  EXPECT_EQ(refusal("zero_axis"), where("zero_axis") + "joint 'j2' has a zero or invalid axis");
  const std::string nan = refusal("nan_origin");
  EXPECT_THAT(nan, HasSubstr(where("nan_origin")));
  EXPECT_THAT(nan, HasSubstr("[nan]"));
  EXPECT_THAT(nan, HasSubstr("joint [j1]"));
  const std::string inf = refusal("inf_limit");
  EXPECT_THAT(inf, HasSubstr("(inf)"));
  EXPECT_THAT(inf, HasSubstr("joint [j1]"));
  EXPECT_EQ(refusal("lower_above_upper"),
            where("lower_above_upper") + "joint 'j1': <limit> lower 1 > upper -1");
  EXPECT_EQ(refusal("mimic_loop", "tip"), where("mimic_loop") + "mimic loop fa -> fb -> fa");
  EXPECT_EQ(
      refusal("mimic_missing", "tip"),
      where("mimic_missing") + "joint 'finger' mimics 'thumb', which is not a joint of the URDF");
  EXPECT_THAT(
      refusal("mimic_on_chain"),
      HasSubstr(where("mimic_on_chain") + "joint 'j2' on the chain base -> l2 mimics 'j1'"));
  EXPECT_EQ(refusal("empty"), where("empty") + "the file is empty");
  EXPECT_EQ(refusal("does_not_exist"),
            "robot file '" + urdf("does_not_exist") + "' does not exist");
}

// Hostile meshes (an absurd scale, an STL claiming 2^32 - 1 facets, files that do not exist)
// are the geometry layer's to refuse, where meshes are read (tests/geometry/
// robot_geometry_test.cpp asserts those messages): the chain loads, the URIs kept as written.
TEST(UrdfConformance, HostileMeshesLoadAsChainsForTheGeometryLayerToRefuse) {
  const RobotDescription scale = load("absurd_mesh_scale");
  ASSERT_TRUE(scale.model);
  ASSERT_EQ(scale.link("l1")->visuals.size(), 1u);
  EXPECT_EQ(scale.link("l1")->visuals[0].mesh_uri, "meshes/cube.stl");
  EXPECT_EQ(scale.link("l1")->visuals[0].scale, Eigen::Vector3d::Constant(1e9));
  const RobotDescription count = load("absurd_mesh_count");
  ASSERT_TRUE(count.model);
  ASSERT_EQ(count.link("l1")->collisions.size(), 1u);
  EXPECT_EQ(count.link("l1")->collisions[0].mesh_uri, "meshes/claims_4g_facets.stl");
  const RobotDescription missing = load("missing_mesh");
  ASSERT_TRUE(missing.model);
  EXPECT_EQ(missing.link("base")->visuals[0].mesh_uri, "meshes/gone.obj");
  EXPECT_EQ(missing.link("l1")->visuals[0].mesh_uri, "package://telear_test_pkg/meshes/gone.stl");
}

TEST(UrdfConformance, MalformedTextNeverCrashes) {
  // Truncations of a valid file at every 7th character: each is refused or loads, never crashes.
  const char* text = R"(<robot name="t"><link name="a"><visual><geometry><box size="1 1 1"/>
    </geometry></visual></link><link name="b"/><joint name="j" type="revolute"><parent link="a"/>
    <child link="b"/><origin xyz="0 0 1" rpy="0 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/><mimic joint="j"/></joint></robot>)";
  const std::string full(text);
  for (std::size_t n = 0; n <= full.size(); n += 7) {
    auto model = parse_urdf(full.substr(0, n), "t.urdf");
    if (!model) {
      EXPECT_THAT(model.error().message, HasSubstr("URDF 't.urdf': "));
    }
  }
  // A joint that mimics itself is a loop of one.
  auto self = parse_urdf(full, "t.urdf");
  ASSERT_FALSE(self);
  EXPECT_EQ(self.error().message, "URDF 't.urdf': mimic loop j -> j");
}

// Issue 25: TinyXML 1 (urdfdom's parser) reads past the end of a text cut inside a multi-byte
// UTF-8 character (fuzz/crashes/urdf/utf8_cut_at_the_end.urdf, a heap overflow under ASan);
// text that is not UTF-8 is refused first, with the byte named. Valid UTF-8 names still load.
TEST(UrdfConformance, TextThatIsNotUtf8IsRefusedBeforeTheXmlParserReadsIt) {
  const std::string head = "<robot name=\"r\"><link name=\"a\"/></robot>";
  for (const auto& [text, at] : {std::pair<std::string, std::size_t>{head + "\xD6", head.size()},
                                 {"<robot name=\"\xC0\xAF\"/>", 13},          // an overlong '/'
                                 {"<robot name=\"\xED\xA0\x80\"/>", 13},      // a surrogate
                                 {"<robot name=\"\xF4\x90\x80\x80\"/>", 13},  // past U+10FFFF
                                 {"<robot name=\"\xE2\x82\"/>", 13}}) {  // a cut 3-byte sequence
    auto model = parse_urdf(text, "bytes.urdf");
    ASSERT_FALSE(model) << at;
    EXPECT_EQ(model.error().message,
              "URDF 'bytes.urdf': not UTF-8 text (an invalid byte "
              "sequence at byte " +
                  std::to_string(at) + ")");
  }
  auto utf8 = parse_urdf_description(
      "<robot name=\"bras_\xC3\xA9l\xC3\xA8ve\"><link name=\"a\"/><link name=\"b\"/>"
      "<joint name=\"j\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/>"
      "<axis xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/>"
      "</joint></robot>",
      "utf8.urdf");
  EXPECT_TRUE(utf8) << utf8.error().message;
}

// Issue 25, the fuzzer's first findings (fuzz/crashes/urdf/): URDFs whose joints form a cycle
// made urdfdom build links that own each other and never free them. The graph is now checked
// before urdfdom builds it; these name the cycle (the fuzz replay under ASan would name a leak).
TEST(UrdfConformance, JointCyclesAreRefusedBeforeUrdfdomBuildsThem) {
  const std::string links = "<link name=\"base\"/><link name=\"a\"/><link name=\"b\"/>";
  const auto joint = [](const std::string& name, const std::string& parent,
                        const std::string& child) {
    return "<joint name=\"" + name + "\" type=\"revolute\"><parent link=\"" + parent +
           "\"/><child link=\"" + child +
           "\"/><axis xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" "
           "velocity=\"1\"/></joint>";
  };
  const auto robot = [&](const std::string& joints) {
    return "<robot name=\"r\">" + links + joints + "</robot>";
  };
  auto self = parse_urdf(robot(joint("j0", "base", "a") + joint("j1", "b", "b")), "self.urdf");
  ASSERT_FALSE(self);
  EXPECT_EQ(self.error().message,
            "URDF 'self.urdf': joint 'j1' has link 'b' as both its parent and its child; a URDF "
            "must be a tree");
  // a -> b -> a, hanging from nothing: no link is the child of two joints.
  auto loop = parse_urdf(robot(joint("j1", "a", "b") + joint("j2", "b", "a")), "loop.urdf");
  ASSERT_FALSE(loop);
  EXPECT_EQ(loop.error().message,
            "URDF 'loop.urdf': the joints form a cycle through link 'a'; a URDF must be a tree");
  auto twice = parse_urdf_description(
      robot(joint("j0", "base", "a") + joint("j1", "a", "b") + joint("j2", "b", "a")), "two.urdf");
  ASSERT_FALSE(twice);
  EXPECT_EQ(twice.error().message,
            "URDF 'two.urdf': link 'a' is the child of several joints (j0, j2); a URDF must be a "
            "tree (is there a cycle?)");
  // A tree is untouched by the check.
  EXPECT_TRUE(parse_urdf(robot(joint("j0", "base", "a") + joint("j1", "a", "b")), "tree.urdf"));
}

}  // namespace
}  // namespace telear::core
