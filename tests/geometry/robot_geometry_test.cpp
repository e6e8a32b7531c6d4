// A URDF robot's body and collision geometry from a hand-built RobotDescription: links on one
// frame merge into one part, a finger link moves with the opening (matrices only), missing
// meshes fail or get stand-ins with a warning, collision shapes fall back to the visuals.

#include "telear/geometry/robot_geometry.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "telear/core/arm_body_pose.hpp"
#include "telear/core/robot_description.hpp"
#include "test_util/mesh_test_files.hpp"
#include "test_util/test_util.hpp"

namespace telear::geometry {
namespace {

using ::testing::HasSubstr;
using namespace test_files;
using Kind = core::GeometryElement::Kind;

core::RobotModelPtr two_joint_arm() {
  core::RobotModel::Description d;
  d.name = "two";
  for (int k = 0; k < 2; ++k) {
    core::Joint j;
    j.name = "j" + std::to_string(k + 1);
    j.after.translation() = Eigen::Vector3d(0, 0, 0.3);
    j.limits = {-3.0, 3.0, 1.0, 1.0};
    d.joints.push_back(j);
  }
  auto model = core::RobotModel::create(d);
  EXPECT_TRUE(model) << model.error().message;
  return std::make_shared<const core::RobotModel>(std::move(*model));
}

core::GeometryElement box(const Eigen::Vector3d& size) {
  core::GeometryElement e;
  e.kind = Kind::kBox;
  e.box_size = size;
  return e;
}

core::GeometryElement mesh(const std::string& uri) {
  core::GeometryElement e;
  e.kind = Kind::kMesh;
  e.mesh_uri = uri;
  return e;
}

core::RobotLink link(const std::string& name, int frame) {
  core::RobotLink l;
  l.name = name;
  l.frame = frame;
  return l;
}

class RobotGeometryTest : public ::testing::Test {
 protected:
  void SetUp() override {
    tmp.write("pkgs/arm/meshes/cube.stl", binary_stl_cube());
    options.package_paths = {(tmp.path() / "pkgs").string()};
    options.ros_package_path = std::vector<std::string>{};  // the test's paths only
    options.segments = 8;

    d.model = two_joint_arm();
    d.name = "two";
    d.urdf_path = (tmp.path() / "two.urdf").string();
    core::RobotLink base = link("base", 0);
    base.visuals.push_back(box({0.2, 0.2, 0.1}));
    // Two links on frame 1: the cube link itself and a cover 0.5 m up it (a fixed joint).
    core::RobotLink upper = link("upper", 1);
    upper.visuals.push_back(mesh("package://arm/meshes/cube.stl"));
    core::RobotLink cover = link("cover", 1);
    core::AttachmentStep up;
    up.fixed.translation() = Eigen::Vector3d(0, 0, 0.5);
    cover.steps.push_back(up);
    core::GeometryElement sphere;
    sphere.kind = Kind::kSphere;
    sphere.radius = 0.1;
    sphere.rgba = Eigen::Vector4f(1, 0, 0, 1);
    cover.visuals.push_back(sphere);
    // A finger on frame 2: 0.1 m out, then a prismatic gripper joint along z.
    core::RobotLink finger = link("finger", 2);
    core::AttachmentStep out, slide;
    out.fixed.translation() = Eigen::Vector3d(0, 0, 0.1);
    slide.gripper_joint = 0;
    finger.steps = {out, slide};
    finger.visuals.push_back(box({0.01, 0.02, 0.05}));
    d.links = {base, upper, cover, finger};
    core::GripperJoint joint;
    joint.name = "finger_joint";
    joint.type = core::JointType::kPrismatic;
    joint.closed = 0.0;
    joint.open = 0.04;
    d.gripper = core::Gripper{{joint}, 0.08};
  }

  TempDir tmp;
  GeometryOptions options;
  core::RobotDescription d;
};

TEST_F(RobotGeometryTest, LinksOnOneFrameMergeIntoOnePartMovedIntoThatFrame) {
  auto body = body_for(d, options);
  ASSERT_TRUE(body) << body.error().message;
  EXPECT_TRUE(body->warnings.empty());
  const core::BodyDescription& b = body->body;
  ASSERT_EQ(b.link_meshes.size(), 3u);
  EXPECT_EQ(b.link_meshes[0].triangle_count(), static_cast<std::size_t>(core::kBoxTriangleCount));
  EXPECT_EQ(b.link_meshes[1].triangle_count(),
            12u + static_cast<std::size_t>(core::sphere_triangle_count(8)));
  EXPECT_TRUE(b.link_meshes[2].empty());  // only the finger rides there, and it moves
  // The cover's sphere sits 0.5 m up frame 1, red; the cube keeps its grey.
  float top = 0.0f;
  for (const core::MeshVertex& v : b.link_meshes[1].vertices) {
    if (v.colour[0] == 1.0f && v.colour[1] == 0.0f) top = std::max(top, v.position[2]);
  }
  EXPECT_NEAR(top, 0.6f, 1e-5f);

  const core::ArmBody arm = core::build_arm_body(b);
  EXPECT_EQ(arm.part_count(), 4);  // 3 frames + the finger
  EXPECT_EQ(arm.parts[3].name, "finger");
}

TEST_F(RobotGeometryTest, TheFingerMovesWithTheOpeningAndItsVerticesDoNot) {
  auto body = body_for(d, options);
  ASSERT_TRUE(body) << body.error().message;
  ASSERT_EQ(body->body.moving_parts.size(), 1u);
  const core::ArmBody arm = core::build_arm_body(body->body);
  const std::vector<core::MeshVertex> before = arm.parts[3].mesh.vertices;
  core::ArmBodyPose pose(*d.model, arm);
  EXPECT_FLOAT_EQ(pose.gripper_opening(), 0.04f);  // half the maximum

  pose.clear_changes();
  pose.set_gripper_opening(0.0f);
  const Eigen::Matrix4f closed = pose.T_base_part(3);
  EXPECT_EQ(pose.changed().first, 3);
  EXPECT_EQ(pose.changed().count, 1);  // the finger only
  pose.set_gripper_opening(0.08f);
  const Eigen::Matrix4f open = pose.T_base_part(3);
  // Frame 2 is 0.6 m up z at q = 0, the finger 0.1 m further, the joint 0 .. 0.04 m.
  EXPECT_NEAR(closed(2, 3), 0.7f, 1e-6f);
  EXPECT_NEAR(open(2, 3) - closed(2, 3), 0.04f, 1e-6f);
  ASSERT_EQ(arm.parts[3].mesh.vertices.size(), before.size());
  EXPECT_EQ(std::memcmp(arm.parts[3].mesh.vertices.data(), before.data(),
                        before.size() * sizeof(core::MeshVertex)),
            0);
  // The pose agrees with the description's own frame -> link transform.
  EXPECT_TRUE(open.isApprox(
      (pose.kinematics().T_base_link[2] * d.T_frame_link(3, 1.0)).matrix().cast<float>(), 1e-6f));
}

TEST_F(RobotGeometryTest, AMissingMeshIsAnErrorNamingLinkUriAndPlaces) {
  d.links[1].visuals[0].mesh_uri = "package://arm/meshes/none.stl";
  auto body = body_for(d, options);
  ASSERT_FALSE(body);
  EXPECT_EQ(body.error().message,
            "link 'upper': mesh 'package://arm/meshes/none.stl' not found (looked in " +
                (tmp.path() / "pkgs/arm").string() +
                "; set ROS_PACKAGE_PATH or add a package path)");
}

TEST_F(RobotGeometryTest, MissingMeshesBecomeStandInsWithAWarning) {
  d.links[1].visuals[0].mesh_uri = "package://arm/meshes/none.stl";
  options.missing_meshes = MissingMeshes::kPrimitives;
  auto body = body_for(d, options);
  ASSERT_TRUE(body) << body.error().message;
  ASSERT_EQ(body->warnings.size(), 1u);
  EXPECT_THAT(body->warnings[0],
              HasSubstr("link 'upper': mesh 'package://arm/meshes/none.stl' not found"));
  EXPECT_THAT(body->warnings[0], HasSubstr("; drawn as a sphere"));
  EXPECT_EQ(body->body.link_meshes[1].triangle_count(),
            2u * static_cast<std::size_t>(core::sphere_triangle_count(8)));

  // With a collision box, the stand-in is that box.
  d.links[1].collisions.push_back(box({0.1, 0.1, 0.4}));
  body = body_for(d, options);
  ASSERT_TRUE(body) << body.error().message;
  EXPECT_THAT(body->warnings[0], HasSubstr("; drawn as its collision primitives"));
  EXPECT_EQ(body->body.link_meshes[1].triangle_count(),
            static_cast<std::size_t>(core::kBoxTriangleCount + core::sphere_triangle_count(8)));
}

TEST_F(RobotGeometryTest, InconsistentDescriptionsAreErrors) {
  d.links[1].frame = 5;
  auto body = body_for(d, options);
  ASSERT_FALSE(body);
  EXPECT_EQ(body.error().message, "link 'upper': rides on frame 5, but the chain has frames 0..2");
  d.links[1].frame = 1;
  d.links[3].steps[1].gripper_joint = 2;
  body = body_for(d, options);
  ASSERT_FALSE(body);
  EXPECT_EQ(body.error().message,
            "link 'finger': moves with gripper joint 2, but the gripper has 1 joints");
  d.links[3].steps[1].gripper_joint = 0;
  d.links[0].visuals[0].box_size.x() = 0.0;
  body = body_for(d, options);
  ASSERT_FALSE(body);
  EXPECT_EQ(body.error().message, "link 'base': box size must be positive on every axis");
  options.segments = 2;
  EXPECT_EQ(body_for(d, options).error().message, "segments must be at least 3, got 2");
}

TEST_F(RobotGeometryTest, ADhRobotKeepsItsPrimitiveBody) {
  d.links.clear();
  auto body = body_for(d, options);
  ASSERT_TRUE(body) << body.error().message;
  EXPECT_EQ(body->body.source, "default");
  EXPECT_EQ(body->body.links.size(), 3u);
  EXPECT_TRUE(body->body.link_meshes.empty());
}

TEST_F(RobotGeometryTest, CollisionShapesKeepPrimitivesAndFallBackToVisuals) {
  d.links[0].collisions.push_back(box({0.3, 0.3, 0.1}));
  auto geometry = collision_geometry_for(d, options);
  ASSERT_TRUE(geometry) << geometry.error().message;
  ASSERT_EQ(geometry->links.size(), 4u);
  const LinkCollision& base = geometry->links[0];
  EXPECT_FALSE(base.from_visual);
  ASSERT_EQ(base.shapes.size(), 1u);
  EXPECT_EQ(base.shapes[0].kind, Kind::kBox);
  EXPECT_TRUE(base.shapes[0].box_size.isApprox(Eigen::Vector3d(0.3, 0.3, 0.1)));
  EXPECT_TRUE(base.shapes[0].mesh.empty());
  const LinkCollision& upper = geometry->links[1];
  EXPECT_TRUE(upper.from_visual);
  EXPECT_EQ(upper.frame, 1);
  ASSERT_EQ(upper.shapes.size(), 1u);
  EXPECT_EQ(upper.shapes[0].kind, Kind::kMesh);
  EXPECT_EQ(upper.shapes[0].mesh.triangle_count(), 12u);

  d.links[1].visuals[0].mesh_uri = "package://arm/meshes/none.stl";
  EXPECT_THAT(collision_geometry_for(d, options).error().message,
              HasSubstr("link 'upper': mesh 'package://arm/meshes/none.stl' not found"));
  options.missing_meshes = MissingMeshes::kPrimitives;
  geometry = collision_geometry_for(d, options);
  ASSERT_TRUE(geometry) << geometry.error().message;
  EXPECT_EQ(geometry->links[1].shapes[0].kind, Kind::kSphere);
  ASSERT_EQ(geometry->warnings.size(), 1u);
  EXPECT_THAT(geometry->warnings[0], HasSubstr("a sphere stands in for its collision shape"));
}

// The URDF conformance set's hostile meshes (tests/data/urdf; their chains load in core, see
// tests/core/urdf_conformance_test.cpp): each refused here, where meshes are read, with a
// message naming the link, the URI and where it was looked for.
std::string conformance_urdf(const std::string& name) {
  return std::filesystem::path(test::data_path("../tests/data/urdf/" + name + ".urdf"))
      .lexically_normal()
      .string();
}

core::RobotDescription conformance_description(const std::string& name) {
  auto d = core::load_robot_description({conformance_urdf(name), "", {}});
  EXPECT_TRUE(d) << d.error().message;
  return d ? std::move(d).value() : core::RobotDescription{};
}

// The file a relative mesh URI of a conformance URDF resolves to.
std::string beside(const core::RobotDescription& d, const std::string& relative) {
  return std::filesystem::absolute(std::filesystem::path(d.urdf_path).parent_path() / relative)
      .lexically_normal()
      .string();
}

TEST(ConformanceMeshes, AnAbsurdMeshScaleIsRefusedNamingLinkUriAndFile) {
  const core::RobotDescription d = conformance_description("absurd_mesh_scale");
  ASSERT_TRUE(d.model);
  const std::string expected =
      "link 'l1': mesh 'meshes/cube.stl': mesh file " + beside(d, "meshes/cube.stl") +
      ": mesh scale 1e+09 1e+09 1e+09 is absurd: each axis must be within 1e-06 .. 1000 in "
      "magnitude";
  auto body = body_for(d);
  ASSERT_FALSE(body);
  EXPECT_EQ(body.error().message, expected);
  // The collision geometry falls back to that visual, and is refused the same way.
  auto collision = collision_geometry_for(d);
  ASSERT_FALSE(collision);
  EXPECT_EQ(collision.error().message, expected);
}

TEST(ConformanceMeshes, AMeshClaimingBillionsOfFacetsIsRefusedWithoutTrustingTheClaim) {
  const core::RobotDescription d = conformance_description("absurd_mesh_count");
  ASSERT_TRUE(d.model);
  const std::string file = beside(d, "meshes/claims_4g_facets.stl");
  for (const std::string& message :
       {body_for(d).error().message, collision_geometry_for(d).error().message}) {
    // assimp's reason follows (the file is too small for the facets it claims).
    EXPECT_THAT(message, ::testing::StartsWith("link 'l1': mesh 'meshes/claims_4g_facets.stl': "
                                               "mesh file " +
                                               file + " is not a readable mesh ("));
  }
}

TEST(ConformanceMeshes, AMeshOverTheByteOrVertexLimitIsRefusedNamingLinkUriAndFile) {
  core::RobotDescription d = conformance_description("absurd_mesh_scale");
  ASSERT_TRUE(d.model);
  d.links[1].visuals[0].scale = Eigen::Vector3d::Ones();  // the cube as it is: 1 cm
  const std::string file = beside(d, "meshes/cube.stl");
  GeometryOptions options;
  ASSERT_TRUE(body_for(d, options)) << "the cube itself loads";
  options.limits.max_file_bytes = 1000;
  EXPECT_EQ(body_for(d, options).error().message,
            "link 'l1': mesh 'meshes/cube.stl': mesh file " + file + " is " +
                std::to_string(std::filesystem::file_size(file)) +
                " bytes, over the limit of 1000 bytes");
  options.limits = {};
  options.limits.max_vertices = 23;  // 24: each face's corners keep the face's normal
  EXPECT_EQ(body_for(d, options).error().message, "link 'l1': mesh 'meshes/cube.stl': mesh file " +
                                                      file +
                                                      ": 24 vertices exceed the limit of 23");
}

TEST(ConformanceMeshes, MissingMeshFilesAreRefusedNamingLinkUriAndWhereTheyWereLookedFor) {
  const core::RobotDescription d = conformance_description("missing_mesh");
  ASSERT_TRUE(d.model);
  GeometryOptions options;
  options.package_paths = {std::filesystem::path(d.urdf_path).parent_path().string()};
  options.ros_package_path = std::vector<std::string>{};
  const std::string relative =
      "link 'base': mesh 'meshes/gone.obj' not found: " +
      (std::filesystem::path(d.urdf_path).parent_path() / "meshes/gone.obj").string() +
      " does not exist";
  const std::string by_package =
      "link 'l1': mesh 'package://telear_test_pkg/meshes/gone.stl' not found (looked in " +
      (std::filesystem::path(d.urdf_path).parent_path() / "telear_test_pkg").string() +
      "; set ROS_PACKAGE_PATH or add a package path)";
  auto body = body_for(d, options);
  ASSERT_FALSE(body);
  EXPECT_EQ(body.error().message, relative);  // the first link's, in file order
  auto collision = collision_geometry_for(d, options);
  ASSERT_FALSE(collision);
  EXPECT_EQ(collision.error().message, relative);
  // With stand-ins, each is a warning and the body is drawn.
  options.missing_meshes = MissingMeshes::kPrimitives;
  auto drawn = body_for(d, options);
  ASSERT_TRUE(drawn) << drawn.error().message;
  ASSERT_EQ(drawn->warnings.size(), 2u);
  EXPECT_EQ(drawn->warnings[0], relative + "; drawn as a sphere");
  EXPECT_EQ(drawn->warnings[1], by_package + "; drawn as a sphere");
}

}  // namespace
}  // namespace telear::geometry
