// Continuous checking along a trajectory (geometry/trajectory_collision.hpp): a fast motion
// through a 2 mm plate is found although no sample of the trajectory touches it, the contact
// time lies between the two samples around it, and the clearance along a motion that passes an
// obstacle matches the analytic closest approach.

#include "telear/geometry/trajectory_collision.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "telear/core/kinematics.hpp"

namespace telear::geometry {
namespace {

using Kind = core::GeometryElement::Kind;

constexpr double kReach = 1.0, kProbeRadius = 0.005;

// One revolute joint about z (3 rad/s, 30 rad/s^2); a 5 mm sphere rides 1 m out on frame 1.
RobotCollisionModel probe_robot() {
  core::RobotModel::Description d;
  d.name = "one";
  core::Joint j;
  j.name = "j1";
  j.after.translation() = Eigen::Vector3d(kReach, 0, 0);
  j.limits = {-3.0, 3.0, 3.0, 30.0};
  d.joints.push_back(j);
  auto model = core::RobotModel::create(d);
  EXPECT_TRUE(model) << model.error().message;
  RobotCollisionModel m;
  m.model = std::make_shared<const core::RobotModel>(std::move(*model));
  CollisionBody b;
  b.name = "probe";
  b.frame = 1;
  CollisionShape s;
  s.kind = Kind::kSphere;
  s.radius = kProbeRadius;
  b.shapes.push_back(s);
  b.radius_about_frame_m = kProbeRadius;
  m.bodies.push_back(b);
  m.lever = {{kReach + kProbeRadius}};
  return m;
}

core::Trajectory sweep(double from, double to) {
  Eigen::VectorXd a(1), b(1);
  a << from;
  b << to;
  auto model = probe_robot().model;
  auto trajectory = core::Trajectory::create(*model, {{a}, {b}});
  EXPECT_TRUE(trajectory) << trajectory.error().message;
  return std::move(*trajectory);
}

CollisionChecker checker_with(const core::WorkspaceObject& object) {
  core::Workspace w;
  w.objects.push_back(object);
  auto checker = CollisionChecker::create(probe_robot(), w, AllowedCollisionMatrix{});
  EXPECT_TRUE(checker) << checker.error().message;
  return std::move(*checker);
}

TEST(TrajectoryCollisionTest, AFastMotionThroughAThinPlateIsFoundWhereTheSamplesMissIt) {
  const core::Trajectory trajectory = sweep(-0.5, 0.5);
  auto samples = trajectory.sampled(50.0);  // what the session would send, every 20 ms
  ASSERT_TRUE(samples) << samples.error().message;
  // Two samples around the middle, at full speed: 60 mm of arc apart.
  std::size_t k = 0;
  while (samples->q[k + 1][0] < 0.0) ++k;
  const double a0 = samples->q[k][0], a1 = samples->q[k + 1][0];
  ASSERT_GT(kReach * (a1 - a0), 0.05);
  // A 2 mm plate across the path halfway between them.
  const double mid = 0.5 * (a0 + a1);
  core::WorkspaceObject plate;
  plate.name = "plate";
  plate.shape = core::ShapeKind::kBox;
  plate.size_m = Eigen::Vector3d(0.2, 0.002, 0.2);  // radial, tangential, vertical
  plate.T_base_object.linear() =
      Eigen::AngleAxisd(mid, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  plate.T_base_object.translation() = Eigen::Vector3d(std::cos(mid), std::sin(mid), 0.0) * kReach;
  CollisionChecker checker = checker_with(plate);

  // Naive: no sample touches it.
  for (std::size_t i = 0; i < samples->q.size(); ++i) {
    ASSERT_TRUE(checker.check(samples->q[i], 1.0).collision_free()) << "sample " << i;
  }
  // Continuous: the contact, between the two samples.
  auto report = check_trajectory(checker, trajectory);
  ASSERT_TRUE(report) << report.error().message;
  ASSERT_EQ(report->collisions.size(), 1u);
  const PlanCollision& c = report->collisions[0];
  EXPECT_EQ(c.body, "probe");
  EXPECT_EQ(c.other, "plate");
  EXPECT_FALSE(c.self);
  EXPECT_EQ(c.segment, 0);
  EXPECT_GT(c.time_s, samples->times[k]);
  EXPECT_LT(c.time_s, samples->times[k + 1]);
  // First touch: the probe's front 1 mm + 5 mm before the plate's centre plane.
  Eigen::VectorXd q;
  trajectory.sample(c.time_s, q);
  const double arc_to_plane = kReach * (mid - q[0]);
  EXPECT_NEAR(arc_to_plane, 0.001 + kProbeRadius, 2e-4);
  // It passes right through: the deepest sampled penetration is most of the plate's 2 mm.
  EXPECT_GT(c.depth_m, 0.001);
  EXPECT_EQ(report->min_clearance.distance_m, 0.0);
  EXPECT_FALSE(report->collision_free());
}

TEST(TrajectoryCollisionTest, TheClearanceAlongAMotionMatchesTheClosestApproach) {
  core::WorkspaceObject ball;
  ball.name = "ball";
  ball.shape = core::ShapeKind::kSphere;
  ball.radius_m = 0.05;
  ball.T_base_object.translation() = Eigen::Vector3d(1.2, 0.0, 0.0);
  CollisionChecker checker = checker_with(ball);
  auto report = check_trajectory(checker, sweep(-0.8, 0.6));
  ASSERT_TRUE(report) << report.error().message;
  EXPECT_TRUE(report->collision_free());
  const double closest = 1.2 - kReach - kProbeRadius - ball.radius_m;  // at q = 0
  EXPECT_GE(report->min_clearance.distance_m, closest - 1e-6);
  EXPECT_NEAR(report->min_clearance.distance_m, closest, 1e-3);
  EXPECT_EQ(report->min_clearance.body, "probe");
  EXPECT_EQ(report->min_clearance.other, "ball");
  // Near q = 0 in time: the sweep's time at q = 0, from the trajectory.
  Eigen::VectorXd q;
  sweep(-0.8, 0.6).sample(report->min_clearance.time_s, q);
  EXPECT_NEAR(q[0], 0.0, 0.05);
}

TEST(TrajectoryCollisionTest, BadOptionsAndAWrongRobotAreRefused) {
  core::WorkspaceObject ball;
  ball.name = "ball";
  ball.shape = core::ShapeKind::kSphere;
  ball.radius_m = 0.05;
  CollisionChecker checker = checker_with(ball);
  TrajectoryCheckOptions options;
  options.resolution_m = -1.0;
  auto bad = check_trajectory(checker, sweep(0, 1), options);
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().message, "collision check: resolution_m must be a positive number, got -1");
  options = {};
  options.refresh_fraction = 1.0;
  bad = check_trajectory(checker, sweep(0, 1), options);
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().message, "collision check: refresh_fraction must lie in (0, 1), got 1");
}

}  // namespace
}  // namespace telear::geometry
