// Collision checking at one configuration (geometry/collision_checker.hpp) against analytic
// distances of primitives, a loaded workspace mesh, an object held in the gripper, and the
// shipped arms at rest (no false contacts between their links) and folded (self-contact).

#include "telear/geometry/collision_checker.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "telear/core/kinematics.hpp"
#include "telear/core/pose.hpp"
#include "telear/geometry/workspace_meshes.hpp"
#include "test_util/mesh_test_files.hpp"
#include "test_util/test_util.hpp"

namespace telear::geometry {
namespace {

using ::testing::HasSubstr;
using Kind = core::GeometryElement::Kind;

// One revolute joint about z; frame 1 sits `reach` m out along x.
core::RobotModelPtr one_joint_arm(double reach) {
  core::RobotModel::Description d;
  d.name = "one";
  core::Joint j;
  j.name = "j1";
  j.after.translation() = Eigen::Vector3d(reach, 0, 0);
  j.limits = {-3.0, 3.0, 3.0, 30.0};
  d.joints.push_back(j);
  auto model = core::RobotModel::create(d);
  EXPECT_TRUE(model) << model.error().message;
  return std::make_shared<const core::RobotModel>(std::move(*model));
}

CollisionShape sphere_shape(double r, const Eigen::Vector3d& at = Eigen::Vector3d::Zero()) {
  CollisionShape s;
  s.kind = Kind::kSphere;
  s.radius = r;
  s.T_link_shape.translation() = at;
  return s;
}

// A robot of one body on `frame` of the one-joint arm, levers filled as robot_collision_model
// would (frame 1: reach + body radius).
RobotCollisionModel probe_robot(std::vector<CollisionShape> shapes, int frame, double reach = 1.0,
                                const Eigen::Isometry3d& T = Eigen::Isometry3d::Identity()) {
  RobotCollisionModel m;
  m.model = one_joint_arm(reach);
  CollisionBody b;
  b.name = "probe";
  b.frame = frame;
  b.T_frame_body = T;
  b.shapes = std::move(shapes);
  for (const CollisionShape& s : b.shapes) {
    CollisionShape posed = s;
    posed.T_link_shape = T * s.T_link_shape;
    b.radius_about_frame_m = std::max(b.radius_about_frame_m, shape_radius_about_origin(posed));
  }
  m.bodies.push_back(b);
  m.lever = {{frame == 1 ? reach + b.radius_about_frame_m : 0.0}};
  return m;
}

core::WorkspaceObject box_object(const std::string& name, const Eigen::Vector3d& size,
                                 const Eigen::Isometry3d& T) {
  core::WorkspaceObject o;
  o.name = name;
  o.shape = core::ShapeKind::kBox;
  o.size_m = size;
  o.T_base_object = T;
  return o;
}

CollisionChecker checker_for(RobotCollisionModel robot,
                             std::vector<core::WorkspaceObject> objects) {
  core::Workspace w;
  w.name = "test";
  w.objects = std::move(objects);
  auto checker = CollisionChecker::create(std::move(robot), w, AllowedCollisionMatrix{});
  EXPECT_TRUE(checker) << checker.error().message;
  return std::move(*checker);
}

Eigen::Isometry3d pose(const Eigen::Vector3d& xyz, const Eigen::Vector3d& rpy) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = core::rotation_from_rpy(rpy.x(), rpy.y(), rpy.z());
  T.translation() = xyz;
  return T;
}

// Sphere to box: the distance from the centre to its closest point on the box, less r.
TEST(CollisionCheckerTest, SphereToBoxClearanceMatchesTheAnalyticDistance) {
  const Eigen::Isometry3d T_box = pose({1.0, 0.2, 0.5}, {0.3, -0.2, 0.7});
  const Eigen::Vector3d size(0.2, 0.4, 0.6);
  const double r = 0.05;
  const Eigen::Vector3d centre(0.6, -0.3, 0.9);
  auto checker =
      checker_for(probe_robot({sphere_shape(r, centre)}, 0), {box_object("box", size, T_box)});
  const CollisionReport report = checker.check(Eigen::VectorXd::Zero(1));
  ASSERT_TRUE(report.collision_free());
  const Eigen::Vector3d c_box = T_box.inverse() * centre;
  const Eigen::Vector3d closest_box = c_box.cwiseMax(-size / 2).cwiseMin(size / 2);
  const double expected = (c_box - closest_box).norm() - r;
  EXPECT_NEAR(report.min_clearance.distance_m, expected, 1e-6);
  EXPECT_EQ(report.min_clearance.body, "probe");
  EXPECT_EQ(report.min_clearance.other, "box");
  // Witness points: on the box surface, and on the sphere towards it.
  const Eigen::Vector3d on_box = T_box * closest_box;
  EXPECT_LT((report.min_clearance.p_other_base - on_box).norm(), 1e-6);
  // (FCL places the sphere's witness point to about 1e-5 m; the distance itself is exact.)
  const Eigen::Vector3d on_sphere = centre + r * (on_box - centre).normalized();
  EXPECT_LT((report.min_clearance.p_body_base - on_sphere).norm(), 1e-4);
}

// Cylinder (a body) to sphere (an object): radial and axial excess from the cylinder's frame.
TEST(CollisionCheckerTest, CylinderToSphereClearanceMatchesTheAnalyticDistance) {
  CollisionShape cylinder;
  cylinder.kind = Kind::kCylinder;
  cylinder.radius = 0.04;
  cylinder.length = 0.3;
  cylinder.T_link_shape = pose({0.1, 0.0, 0.4}, {0.5, 0.1, 0.0});
  core::WorkspaceObject ball;
  ball.name = "ball";
  ball.shape = core::ShapeKind::kSphere;
  ball.radius_m = 0.07;
  for (const Eigen::Vector3d& centre :
       {Eigen::Vector3d(0.5, 0.1, 0.5), Eigen::Vector3d(0.1, 0.3, 0.9),
        Eigen::Vector3d(0.3, -0.4, 0.2)}) {
    ball.T_base_object = pose(centre, {0, 0, 0});
    auto checker = checker_for(probe_robot({cylinder}, 0), {ball});
    const CollisionReport report = checker.check(Eigen::VectorXd::Zero(1));
    ASSERT_TRUE(report.collision_free());
    const Eigen::Vector3d p = cylinder.T_link_shape.inverse() * centre;
    const double radial = std::max(std::hypot(p.x(), p.y()) - cylinder.radius, 0.0);
    const double axial = std::max(std::abs(p.z()) - cylinder.length / 2, 0.0);
    EXPECT_NEAR(report.min_clearance.distance_m, std::hypot(radial, axial) - ball.radius_m, 1e-6)
        << centre.transpose();
  }
}

TEST(CollisionCheckerTest, ASphereIntoABoxFaceIsAContactOfItsPenetrationDepth) {
  const double r = 0.05, depth = 0.012;
  // Box top face at z = 0.4; the sphere's centre r - depth above it.
  auto checker = checker_for(probe_robot({sphere_shape(r, {0.5, 0.0, 0.4 + r - depth})}, 0),
                             {box_object("table", {1, 1, 0.2}, pose({0.5, 0, 0.3}, {0, 0, 0}))});
  const CollisionReport report = checker.check(Eigen::VectorXd::Zero(1));
  ASSERT_EQ(report.contacts.size(), 1u);
  EXPECT_EQ(report.contacts[0].body, "probe");
  EXPECT_EQ(report.contacts[0].other, "table");
  EXPECT_FALSE(report.contacts[0].self);
  EXPECT_NEAR(report.contacts[0].depth_m, depth, 1e-6);
}

TEST(CollisionCheckerTest, AWorkspaceMeshIsCheckedOnceLoaded) {
  test_files::TempDir dir;
  dir.write("cube.stl", test_files::binary_stl_cube());  // [0, 1]^3
  const std::string path = dir.write("ws.yaml", R"(
objects:
  - {name: block, shape: mesh, file: cube.stl, scale: [0.2, 0.2, 0.2], pose: {xyz: [1, 0, 0]}}
)");
  auto parsed = core::load_workspace_file(path);
  ASSERT_TRUE(parsed) << parsed.error().message;
  // Not loaded: the checker refuses it, naming the object.
  auto refused = CollisionChecker::create(probe_robot({sphere_shape(0.05)}, 0), *parsed, {});
  ASSERT_FALSE(refused);
  EXPECT_THAT(refused.error().message, HasSubstr("object 'block': its mesh is not loaded"));
  auto workspace = load_workspace(path);
  ASSERT_TRUE(workspace) << workspace.error().message;
  // Bounds from the mesh: x 1..1.2, y, z 0..0.2.
  const Eigen::AlignedBox3d bounds = workspace->objects[0].bounds_base();
  EXPECT_NEAR(bounds.max().x(), 1.2, 1e-6);
  auto checker = CollisionChecker::create(probe_robot({sphere_shape(0.05, {0.5, 0.1, 0.1})}, 0),
                                          *workspace, {});
  ASSERT_TRUE(checker) << checker.error().message;
  const CollisionReport report = checker->check(Eigen::VectorXd::Zero(1));
  EXPECT_NEAR(report.min_clearance.distance_m, 0.5 - 0.05, 1e-6);  // to the face x = 1
}

TEST(CollisionCheckerTest, AMissingWorkspaceMeshIsRefusedNamingTheObject) {
  test_files::TempDir dir;
  dir.write("broken.stl", "solid nothing\nendsolid nothing\n");
  const std::string path =
      dir.write("ws.yaml", "objects:\n  - {name: junk, shape: mesh, file: broken.stl}\n");
  auto workspace = load_workspace(path);
  ASSERT_FALSE(workspace);
  EXPECT_THAT(workspace.error().message, HasSubstr(path + ": object 'junk': "));
}

using test::robot_description;

CollisionChecker arm_checker(const std::string& robot, const core::Workspace& workspace = {}) {
  auto checker = make_collision_checker(robot_description(robot), workspace);
  EXPECT_TRUE(checker) << checker.error().message;
  return std::move(*checker);
}

// The shipped arms at their named configurations: links touching at their joints are allowed
// (adjacent, or always in contact), and nothing else touches. ur6's `zero` (stretched out,
// singular) is left out: there the upper arm's tube (0.044..0.134 m high) lies across the
// base's cap (0.076 m high), a genuine contact of the model, tested below.
TEST(CollisionCheckerTest, TheShippedArmsAtTheirNamedConfigurationsHaveNoContacts) {
  for (const std::string robot : {"puma560", "ur6", "arm7"}) {
    CollisionChecker checker = arm_checker(robot);
    EXPECT_GT(checker.pairs().size(), 0u) << robot;
    for (const core::NamedConfiguration& c : checker.robot().model->named_configurations()) {
      // Not a pose the arm can take (the PUMA's qn, arm7's zero): beyond the joint limits.
      const core::RobotModel& model = *checker.robot().model;
      if ((c.q.array() < model.lower_limits().array()).any() ||
          (c.q.array() > model.upper_limits().array()).any()) {
        continue;
      }
      if (robot == "ur6" && c.name == "zero") continue;
      const CollisionReport report = checker.check(c.q);
      for (const Contact& contact : report.contacts) {
        ADD_FAILURE() << robot << " at " << c.name << ": " << contact.body << " touches "
                      << contact.other << " (depth " << contact.depth_m << " m at "
                      << contact.point_base.transpose() << ")";
      }
      EXPECT_GT(report.min_clearance.distance_m, 0.0) << robot << " " << c.name;
    }
  }
}

TEST(CollisionCheckerTest, AdjacentLinksAreAllowedAndCheckedPairsAreNot) {
  CollisionChecker checker = arm_checker("puma560");
  EXPECT_TRUE(checker.allowed().allowed("link1", "link2"));
  EXPECT_TRUE(checker.allowed().allowed("link6", "finger_left"));
  EXPECT_FALSE(checker.allowed().allowed("link0", "link6"));
  for (const CollisionPair& p : checker.pairs()) {
    if (p.other_body < 0) continue;
    EXPECT_FALSE(checker.allowed().allowed(checker.robot().bodies[p.body].name,
                                           checker.robot().bodies[p.other_body].name));
  }
}

// Self-contacts: the one pair named, and no workspace needed.
void expect_self_contact(const std::string& robot, const Eigen::VectorXd& q, const std::string& a,
                         const std::string& b) {
  CollisionChecker checker = arm_checker(robot);
  const CollisionReport report = checker.check(q);
  ASSERT_FALSE(report.collision_free()) << robot;
  bool found = false;
  for (const Contact& c : report.contacts) {
    EXPECT_TRUE(c.self) << c.body << " " << c.other;  // no workspace
    if (std::minmax(c.body, c.other) == std::minmax(a, b)) {
      found = true;
      EXPECT_GT(c.depth_m, 0.0);
    }
  }
  EXPECT_TRUE(found) << robot << ": no contact between " << a << " and " << b;
}

TEST(CollisionCheckerTest, FoldedArmsTouchThemselves) {
  Eigen::VectorXd q(6);
  // ur6 with the elbow folded shut (-172 deg): the forearm lies in the shoulder housing.
  q << 0.856, -1.092, -3.002, 0.257, -2.707, 3.676;
  expect_self_contact("ur6", q, "shoulder_link", "forearm_link");
  // The PUMA's upper arm swung down past the horizontal (-88 deg) into the pedestal.
  q << -0.251, -1.534, -0.430, 0.026, -0.140, -0.632;
  expect_self_contact("puma560", q, "link0", "link2");
  // ur6 stretched out at zero: the upper arm across the base's cap.
  expect_self_contact("ur6", Eigen::VectorXd::Zero(6), "base_link", "upper_arm_link");
}

// The PUMA holding the box: the box moves with the hand, and lowered into the table it is the
// box that touches it.
TEST(CollisionCheckerTest, AnObjectHeldInTheGripperMovesWithItAndIsChecked) {
  Eigen::VectorXd q(6);
  q << 0, 0.5, -0.5, 0, 1.5708, 0;
  // A plate across the tool's z axis, 0.3 m out: beyond the hand's reach.
  auto robot = robot_description("puma560");
  const Eigen::Isometry3d T_base_tool = core::tool_pose(*robot.model, q);
  Eigen::Isometry3d T_plate = T_base_tool;
  T_plate.translation() += 0.3 * T_base_tool.linear().col(2);
  core::Workspace workspace;
  workspace.objects.push_back(box_object("plate", {0.4, 0.4, 0.01}, T_plate));
  CollisionChecker checker = arm_checker("puma560", workspace);
  ASSERT_TRUE(checker.check(q).collision_free());
  CollisionShape box;
  box.kind = Kind::kBox;
  box.box_size = Eigen::Vector3d(0.05, 0.05, 0.6);  // a long bar sticking out of the hand
  box.T_link_shape.translation() = Eigen::Vector3d(0, 0, 0.4);
  ASSERT_TRUE(checker.attach("bar", {box}, Eigen::Isometry3d::Identity()));
  const CollisionReport report = checker.check(q);
  ASSERT_FALSE(report.collision_free());
  EXPECT_EQ(report.contacts[0].body, "bar");
  EXPECT_EQ(report.contacts[0].other, "plate");
  // The wrist rolled a quarter turn: the bar comes along, sideways, and misses the plate.
  Eigen::VectorXd away = q;
  away[3] += 1.5708;
  const CollisionReport turned = checker.check(away);
  for (const Contact& c : turned.contacts) ADD_FAILURE() << c.body << " touches " << c.other;
  const auto again = checker.attach("bar", {box}, Eigen::Isometry3d::Identity());
  ASSERT_FALSE(again);
  EXPECT_EQ(again.error().message, "attach: the robot already has a body named 'bar'");
}

// A matrix stored in the robot file is used as written (plus the adjacent pairs) instead of
// being computed: allowing ur6's base and upper arm removes the contact at its zero pose.
TEST(AllowedCollisionsTest, TheRobotFilesMatrixIsUsedAsWritten) {
  test_files::TempDir dir;
  const std::string robots = std::string(TELEAR_TEST_DATA_DIR) + "/robots";
  const std::string path = dir.write(
      "ur6_acm.yaml", "urdf: " + robots + "/telear_ur6/urdf/ur6.urdf\npackage_paths: [" + robots +
                          "]\ntip: tcp\nallowed_collisions:\n  - [base_link, upper_arm_link]\n");
  auto checker = make_collision_checker(robot_description(path), core::Workspace{});
  ASSERT_TRUE(checker) << checker.error().message;
  EXPECT_TRUE(checker->allowed().allowed("upper_arm_link", "base_link"));
  EXPECT_TRUE(checker->allowed().allowed("base_link", "shoulder_link"));  // adjacent, added
  EXPECT_FALSE(checker->allowed().allowed("base_link", "forearm_link"));
  EXPECT_TRUE(checker->check(Eigen::VectorXd::Zero(6)).collision_free());
}

// Two joints about the base's z axis (the second 0.3 m out): everything on frame 2 turns about
// that axis. A post on the axis is 0.23 m from a ball on frame 2 whatever the joints do (a
// pair at a constant distance: allowed, reason `constant`); a stop beside the axis is at a
// varying distance; a hub (the post with a bump the ball runs into) is at the post's constant
// distance except where the ball touches the bump: it stays checked.
RobotCollisionModel turntable() {
  core::RobotModel::Description d;
  d.name = "turntable";
  for (const double reach : {0.0, 0.3}) {
    core::Joint j;
    j.name = "j" + std::to_string(d.joints.size() + 1);
    j.after.translation() = Eigen::Vector3d(reach, 0, 0);
    j.limits = {-3.0, 3.0, 3.0, 30.0};
    d.joints.push_back(j);
  }
  auto model = core::RobotModel::create(d);
  EXPECT_TRUE(model) << model.error().message;
  RobotCollisionModel m;
  m.model = std::make_shared<const core::RobotModel>(std::move(*model));
  CollisionShape post;
  post.kind = Kind::kCylinder;
  post.radius = 0.05;
  post.length = 0.4;
  const auto body = [&](const std::string& name, int frame, std::vector<CollisionShape> shapes) {
    CollisionBody b;
    b.name = name;
    b.frame = frame;
    b.shapes = std::move(shapes);
    m.bodies.push_back(std::move(b));
  };
  body("post", 0, {post});
  body("stop", 0, {sphere_shape(0.01, {0.0, 0.2, 0.0})});
  body("hub", 0, {post, sphere_shape(0.02, {0.3, 0.0, 0.0})});
  body("ball", 2, {sphere_shape(0.02)});
  update_motion_bounds(m);
  return m;
}

TEST(AllowedCollisionsTest, APairAtAConstantDistanceIsAllowedWithItsReason) {
  const RobotCollisionModel robot = turntable();
  AllowedCollisionOptions options;
  options.samples = 300;
  auto m = compute_allowed_collisions(robot, options);
  ASSERT_TRUE(m) << m.error().message;
  EXPECT_EQ(m->to_yaml(),
            "- [ball, post, constant]\n"  // 0.23 m apart in every sample
            "- [hub, post, adjacent]\n"
            "- [hub, stop, adjacent]\n"
            "- [post, stop, adjacent]\n");
  // ball-stop varies, ball-hub touches the bump in some samples: both still checked.
  EXPECT_FALSE(m->allowed("ball", "stop"));
  EXPECT_FALSE(m->allowed("ball", "hub"));
  auto back = AllowedCollisionMatrix::from_yaml(m->to_yaml(), "acm");
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_EQ(back->pairs()[0].reason, AllowedReason::kConstant);

  // Off, or a tolerance the pair exceeds (FCL's distances are exact to 1e-6 m): checked.
  options.allow_constant = false;
  auto off = compute_allowed_collisions(robot, options);
  ASSERT_TRUE(off) << off.error().message;
  EXPECT_FALSE(off->allowed("ball", "post"));
  options.allow_constant = true;
  options.constant_tolerance_m = -1e-3;
  auto bad = compute_allowed_collisions(robot, options);
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().message,
            "allowed collisions: constant_tolerance_m must be finite and at least 0, got -0.001");
}

TEST(AllowedCollisionsTest, TheMatrixRoundTripsThroughYamlAndRefusesUnknownReasons) {
  AllowedCollisionMatrix m;
  m.allow("b", "a", AllowedReason::kAdjacent);
  m.allow("c", "a", AllowedReason::kAlways);
  m.allow("a", "b", AllowedReason::kUser);  // already allowed: keeps adjacent
  EXPECT_EQ(m.to_yaml(), "- [a, b, adjacent]\n- [a, c, always]\n");
  auto back = AllowedCollisionMatrix::from_yaml(m.to_yaml(), "acm");
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_TRUE(back->allowed("c", "a"));
  EXPECT_FALSE(back->allowed("b", "c"));
  auto bad = AllowedCollisionMatrix::from_yaml("- [a, b, sometimes]\n", "acm");
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().message,
            "acm[0]: unknown reason 'sometimes' (adjacent, always, never, constant or user)");
}

}  // namespace
}  // namespace telear::geometry
