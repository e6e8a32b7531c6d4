// Continuous checking along a trajectory (geometry/trajectory_collision.hpp): a fast motion
// through a 2 mm plate is found although no sample of the trajectory touches it, the contact
// time lies between the two samples around it, and the clearance along a motion that passes an
// obstacle matches the analytic closest approach.

#include "telear/geometry/trajectory_collision.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "telear/core/kinematics.hpp"
#include "telear/core/random_configuration.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/geometry/workspace_meshes.hpp"

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

// The per-pair advancement against brute force on the shipped arms in their table scenes: seeded
// random plans (some through the table or the arm itself), the continuous check and a sampling
// every 1 ms (ur6: 2 ms) of every pair. Where the samples see a contact the continuous check has
// seen it first, at most one sample earlier (it may find it between samples, never after); it finds
// no contact the samples miss except between two samples; and the two minimum clearances agree to a
// millimetre (the continuous check samples a pair near the minimum every max_step_m of motion,
// the brute force every sample).
TEST(TrajectoryCollisionTest, TheContinuousCheckAgreesWithBruteForceOnRandomPlans) {
  for (const std::string robot : {"puma560", "ur6"}) {
    // Meshes cost ~100 us a pair: ur6 sampled every 2 ms.
    const double kDt = robot == "ur6" ? 0.002 : 0.001;
    const int kPlans = robot == "ur6" ? 3 : 4;
    auto description = core::load_robot_description({robot, "", {}});
    ASSERT_TRUE(description) << description.error().message;
    auto workspace = load_workspace(core::default_workspace_file(robot));
    ASSERT_TRUE(workspace) << workspace.error().message;
    auto checker = make_collision_checker(*description, *workspace);
    ASSERT_TRUE(checker) << checker.error().message;
    const core::RobotModel& model = *description->model;
    std::mt19937_64 rng(13);
    int with_contact = 0;
    for (int plan = 0; plan < kPlans; ++plan) {
      std::vector<core::JointWaypoint> waypoints{{core::random_configuration(model, rng)}};
      for (int k = 0; k < 2; ++k) {
        const Eigen::VectorXd to = core::random_configuration(model, rng);
        const Eigen::VectorXd& from = waypoints.back().q;
        waypoints.push_back({from + (to - from).cwiseMax(-0.8).cwiseMin(0.8)});
      }
      auto trajectory = core::Trajectory::create(model, waypoints);
      ASSERT_TRUE(trajectory) << trajectory.error().message;
      auto fast = check_trajectory(*checker, *trajectory);
      ASSERT_TRUE(fast) << fast.error().message;
      const TrajectoryCheckReport brute = check_trajectory_sampled(*checker, *trajectory, kDt);
      const std::string what = robot + " plan " + std::to_string(plan);
      if (!brute.collisions.empty()) {
        ++with_contact;
        ASSERT_FALSE(fast->collisions.empty()) << what;
        EXPECT_LE(fast->collisions[0].time_s, brute.collisions[0].time_s + 1e-9) << what;
        EXPECT_GE(fast->collisions[0].time_s, brute.collisions[0].time_s - kDt) << what;
        EXPECT_EQ(fast->min_clearance.distance_m, 0.0) << what;
      } else {
        // Only a contact shorter than a sample, between two: none of these plans has one.
        EXPECT_TRUE(fast->collisions.empty())
            << what << ": " << fast->collisions[0].body << "/" << fast->collisions[0].other;
        const double tolerance = TrajectoryCheckOptions{}.max_step_m / 2.0;
        EXPECT_NEAR(fast->min_clearance.distance_m, brute.min_clearance.distance_m, tolerance)
            << what;
        EXPECT_NEAR(fast->min_workspace_clearance.distance_m,
                    brute.min_workspace_clearance.distance_m, tolerance)
            << what;
      }
    }
    // Both kinds of plan were compared.
    EXPECT_GT(with_contact, 0) << robot;
    EXPECT_LT(with_contact, kPlans) << robot;
  }
}

}  // namespace
}  // namespace telear::geometry
