// Via waypoints: linear segments with parabolic blends (telear/core/trajectory.hpp,
// telear/core/blended_run.hpp). The limits are checked three ways: the profile's own
// velocity and acceleration, finite differences of its positions on a dense grid, and the
// sampled message through validate_timed_waypoints (the server's check).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "telear/core/angles.hpp"
#include "telear/core/blended_run.hpp"
#include "telear/core/joint_limits.hpp"
#include "telear/core/trajectory.hpp"
#include "test_arms.hpp"
#include "test_util/test_util.hpp"

namespace telear::core {
namespace {

using test::deg;

JointWaypoint via(Eigen::VectorXd q, double min_duration = 0.0) {
  return JointWaypoint(std::move(q), min_duration, std::nullopt, true);
}

Trajectory make(const RobotModel& model, std::vector<JointWaypoint> waypoints,
                const TrajectoryOptions& options = {}) {
  auto trajectory = Trajectory::create(model, std::move(waypoints), options);
  EXPECT_TRUE(trajectory.ok()) << trajectory.error().message;
  return *trajectory;
}

// Random plans: random configurations, about two thirds of the inner ones via points, some
// minimum durations, sometimes a repeated waypoint (a dwell), random scales.
struct RandomPlan {
  std::vector<JointWaypoint> waypoints;
  TrajectoryOptions options;
};

RandomPlan random_plan(const RobotModel& model, std::mt19937_64& rng) {
  std::uniform_int_distribution<int> count(2, 9);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  RandomPlan plan;
  const int n = count(rng);
  for (int i = 0; i < n; ++i) {
    JointWaypoint w{test::random_configuration(model, rng)};
    if (i > 0 && unit(rng) < 0.1) w.q = plan.waypoints.back().q;                // a dwell
    if (i > 0 && unit(rng) < 0.3) w.q = 0.5 * (w.q + plan.waypoints.back().q);  // a short hop
    w.via = unit(rng) < 0.67;
    if (unit(rng) < 0.2) w.min_duration = 3.0 * unit(rng);
    plan.waypoints.push_back(w);
  }
  plan.options.velocity_scale = unit(rng) < 0.5 ? 1.0 : 0.1 + 0.9 * unit(rng);
  plan.options.acceleration_scale = unit(rng) < 0.5 ? 1.0 : 0.1 + 0.9 * unit(rng);
  return plan;
}

// [SECTION] Behaviour on the PUMA

class BlendedTrajectory : public ::testing::Test {
 protected:
  RobotModelPtr model = test::puma560();
};

TEST_F(BlendedTrajectory, AViaPointIsPassedWithoutStoppingAndSoonerThanAStop) {
  const Eigen::VectorXd a = deg({0, 0, 0, 0, 0, 0});
  const Eigen::VectorXd b = deg({60, 30, 0, 0, 0, 0});
  const Eigen::VectorXd c = deg({60, 30, 60, 0, 0, 0});
  const Trajectory stopping = make(*model, {{a}, {b}, {c}});
  const Trajectory blended = make(*model, {{a}, via(b), {c}});
  EXPECT_TRUE(blended.passes_through(1));
  EXPECT_FALSE(stopping.passes_through(1));
  EXPECT_LT(blended.duration(), stopping.duration());
  const TrajectoryPoint at_via = blended.sample(blended.waypoint_times()[1]);
  EXPECT_GT(at_via.qd.norm(), 0.1);  // still moving
  // It cuts the corner by the reported deviation, no more.
  EXPECT_LT((at_via.q - b).cwiseAbs().maxCoeff(), radians_from_degrees(10.0));
  EXPECT_LT((at_via.q - b).cwiseAbs().maxCoeff() - blended.via_deviation(1).maxCoeff(), 1e-12);
  EXPECT_GT(blended.via_deviation(1).maxCoeff(), 0.0);
}

TEST_F(BlendedTrajectory, CollinearViaPointsCruiseThroughAtFullSpeed) {
  // Joint 1 0 -> 30 -> 60 -> 90 deg with via points is one 90 deg move: 90 / 80 + 80 / 480 s,
  // through the via points at 80 deg/s exactly where they are.
  const Trajectory traj = make(*model, {{deg({0, 0, 0, 0, 0, 0})},
                                        via(deg({30, 0, 0, 0, 0, 0})),
                                        via(deg({60, 0, 0, 0, 0, 0})),
                                        {deg({90, 0, 0, 0, 0, 0})}});
  EXPECT_NEAR(traj.duration(), 90.0 / 80.0 + 80.0 / 480.0, 1e-12);
  for (size_t k : {1u, 2u}) {
    const TrajectoryPoint p = traj.sample(traj.waypoint_times()[k]);
    EXPECT_NEAR(p.qd[0], radians_from_degrees(80.0), 1e-12);
    EXPECT_NEAR(p.q[0], traj.waypoints()[k].q[0], 1e-12);
    EXPECT_EQ(traj.via_deviation(k).maxCoeff(), 0.0);
  }
}

TEST_F(BlendedTrajectory, StopWaypointsAreReachedExactlyAtRest) {
  std::mt19937_64 rng(23);
  for (int trial = 0; trial < 50; ++trial) {
    const RandomPlan plan = random_plan(*model, rng);
    const Trajectory traj = make(*model, plan.waypoints, plan.options);
    for (size_t k = 0; k < traj.waypoints().size(); ++k) {
      if (traj.passes_through(k)) continue;
      const TrajectoryPoint p = traj.sample(traj.waypoint_times()[k]);
      EXPECT_EQ(p.q, traj.waypoints()[k].q) << "trial " << trial << " waypoint " << k;
      EXPECT_EQ(p.qd, Eigen::VectorXd::Zero(6)) << "trial " << trial << " waypoint " << k;
    }
    EXPECT_EQ(traj.waypoint_times().front(), 0.0);
    EXPECT_EQ(traj.sample(traj.duration()).q, traj.waypoints().back().q);
  }
}

TEST_F(BlendedTrajectory, ViaPointsAreReachedWithinTheStatedTolerance) {
  // At its nominal time the arm is via_deviation(k) from a via waypoint, which is at most an
  // eighth of the joint's displacements before and after it (docs/trajectory.md).
  std::mt19937_64 rng(29);
  int via_points = 0;
  for (int trial = 0; trial < 100; ++trial) {
    const RandomPlan plan = random_plan(*model, rng);
    const Trajectory traj = make(*model, plan.waypoints, plan.options);
    const auto& w = traj.waypoints();
    for (size_t k = 1; k + 1 < w.size(); ++k) {
      if (!traj.passes_through(k)) {
        EXPECT_EQ(traj.via_deviation(k).maxCoeff(), 0.0);
        continue;
      }
      ++via_points;
      const Eigen::VectorXd miss = (traj.sample(traj.waypoint_times()[k]).q - w[k].q).cwiseAbs();
      const Eigen::VectorXd bound =
          ((w[k].q - w[k - 1].q).cwiseAbs() + (w[k + 1].q - w[k].q).cwiseAbs()) / 8.0;
      for (int j = 0; j < 6; ++j) {
        ASSERT_NEAR(miss[j], traj.via_deviation(k)[j], 1e-12) << trial << " " << k << " " << j;
        ASSERT_LE(miss[j], bound[j] + 1e-12) << trial << " " << k << " " << j;
      }
    }
  }
  EXPECT_GT(via_points, 100);
}

TEST_F(BlendedTrajectory, ViaFlagsWithoutMotionAroundThemAreStops) {
  const Eigen::VectorXd a = deg({0, 0, 0, 0, 0, 0});
  const Eigen::VectorXd b = deg({20, 0, 0, 0, 0, 0});
  // First and last waypoints, and a via point before a dwell, are stops.
  const Trajectory traj = make(*model, {via(a), via(b), via(b, 0.5), via(a)});
  for (size_t k = 0; k < 4; ++k) EXPECT_FALSE(traj.passes_through(k)) << k;
  const Trajectory plain = make(*model, {{a}, {b}, {b, 0.5}, {a}});
  EXPECT_EQ(traj.waypoint_times(), plain.waypoint_times());
  for (double t = 0.0; t < plain.duration(); t += 0.01) {
    EXPECT_EQ(traj.sample(t).q, plain.sample(t).q) << t;
  }
}

TEST_F(BlendedTrajectory, MinimumDurationsAndGripperCommandsHoldOnViaPoints) {
  JointWaypoint slow = via(deg({30, 0, 0, 0, 0, 0}), 2.0);
  slow.gripper = 0.25;
  const Trajectory traj =
      make(*model, {{deg({0, 0, 0, 0, 0, 0})}, slow, {deg({30, 40, 0, 0, 0, 0}), 1.5}});
  ASSERT_TRUE(traj.passes_through(1));
  // Up to rounding: the edge segments' durations come from a quadratic's root.
  EXPECT_GE(traj.waypoint_times()[1], 2.0 * (1 - 1e-12));
  EXPECT_GE(traj.waypoint_times()[2] - traj.waypoint_times()[1], 1.5 * (1 - 1e-12));
  ASSERT_EQ(traj.gripper_events().size(), 1u);
  EXPECT_EQ(traj.gripper_events()[0].time, traj.waypoint_times()[1]);
  EXPECT_EQ(traj.gripper_at(traj.waypoint_times()[1]), 0.25);
}

TEST_F(BlendedTrajectory, PositionAndVelocityAreContinuous) {
  std::mt19937_64 rng(31);
  const double h = 1e-7;
  for (int trial = 0; trial < 20; ++trial) {
    const RandomPlan plan = random_plan(*model, rng);
    const Trajectory traj = make(*model, plan.waypoints, plan.options);
    const double a_max = traj.acceleration_limits().maxCoeff();
    for (double t = 0.0; t <= traj.duration(); t += 0.0037) {
      const TrajectoryPoint before = traj.sample(t - h);
      const TrajectoryPoint after = traj.sample(t + h);
      ASSERT_LT((after.q - before.q).cwiseAbs().maxCoeff(), 2 * h * 4.0) << trial << " " << t;
      ASSERT_LT((after.qd - before.qd).cwiseAbs().maxCoeff(), 2 * h * a_max * (1 + 1e-6) + 1e-12)
          << trial << " " << t;
    }
  }
}

// [SECTION] Limits on random plans, three arms

struct LimitsCase {
  const char* name;
  RobotModel (*make)();
};

class BlendedLimits : public ::testing::TestWithParam<LimitsCase> {};

TEST_P(BlendedLimits, RandomPlansNeverExceedVelocityOrAccelerationLimits) {
  const RobotModel model = GetParam().make();
  std::mt19937_64 rng(37);
  int blended = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const RandomPlan plan = random_plan(model, rng);
    const Trajectory traj = make(model, plan.waypoints, plan.options);
    const Eigen::VectorXd v = traj.velocity_limits();
    const Eigen::VectorXd a = traj.acceleration_limits();
    for (size_t k = 0; k < traj.waypoints().size(); ++k) blended += traj.passes_through(k);
    // Analytic: the profile's own peaks (rounding: a relative 1e-12).
    const Eigen::VectorXd peak_v = traj.peak_velocities();
    const Eigen::VectorXd peak_a = traj.peak_accelerations();
    for (int j = 0; j < model.dof(); ++j) {
      ASSERT_LE(peak_v[j], v[j] * (1 + 1e-12)) << "trial " << trial << " joint " << j;
      ASSERT_LE(peak_a[j], a[j] * (1 + 1e-12)) << "trial " << trial << " joint " << j;
    }
    // Dense samples: velocity and acceleration as reported, and finite differences of the
    // positions, which do not trust sample()'s qd and qdd. With h = 1 ms and positions near
    // 1 rad, rounding adds about 1e-16 / h^2 = 1e-10 rad/s^2 to a second difference.
    const double h = 1e-3;
    Eigen::VectorXd q0, q1, q2, qd, qdd;
    traj.sample(-h, q0);
    traj.sample(0.0, q1);
    for (double t = 0.0; t <= traj.duration() + h; t += h) {
      traj.sample(t + h, q2, &qd, &qdd);
      ASSERT_TRUE(within_limits(model, q2)) << "trial " << trial << " t " << t;
      for (int j = 0; j < model.dof(); ++j) {
        ASSERT_LE(std::abs(qd[j]), v[j] * (1 + 1e-12)) << trial << " " << t << " " << j;
        ASSERT_LE(std::abs(qdd[j]), a[j] * (1 + 1e-12)) << trial << " " << t << " " << j;
        ASSERT_LE(std::abs(q2[j] - q1[j]) / h, v[j] * (1 + 1e-9) + 1e-9)
            << trial << " " << t << " " << j;
        ASSERT_LE(std::abs(q2[j] - 2 * q1[j] + q0[j]) / (h * h), a[j] * (1 + 1e-9) + 1e-6)
            << trial << " " << t << " " << j;
      }
      q0 = q1;
      q1 = q2;
    }
    // The message form passes the server's check at the message rate.
    const auto sampled = traj.sampled(100.0);
    ASSERT_TRUE(sampled.ok()) << sampled.error().message;
    const Status valid = validate_timed_waypoints(model, *sampled);
    ASSERT_TRUE(valid.ok()) << "trial " << trial << ": " << valid.error().message;
  }
  EXPECT_GT(blended, 50);
}

RobotModel puma() {
  return *test::puma560();
}
RobotModel ur() {
  return test_arms::ur_type();
}
RobotModel panda() {
  return test_arms::panda_like();
}

INSTANTIATE_TEST_SUITE_P(Arms, BlendedLimits,
                         ::testing::Values(LimitsCase{"puma560", &puma}, LimitsCase{"ur_type", &ur},
                                           LimitsCase{"panda_like", &panda}),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(BlendedLimitsSummary, BlendingIsFasterThanStoppingOnRandomPlans) {
  // Not a guarantee of the method (a corner may slow both its segments), but what it is for:
  // on random all-via plans the blended trajectory is never slower than stopping everywhere.
  const RobotModelPtr model = test::puma560();
  std::mt19937_64 rng(41);
  double stop_total = 0.0, blend_total = 0.0;
  int via_points = 0, passed = 0;
  for (int trial = 0; trial < 100; ++trial) {
    RandomPlan plan = random_plan(*model, rng);
    for (auto& w : plan.waypoints) w.via = false;
    const Trajectory stopping = make(*model, plan.waypoints, plan.options);
    for (auto& w : plan.waypoints) w.via = true;
    const Trajectory blended = make(*model, plan.waypoints, plan.options);
    EXPECT_LE(blended.duration(), stopping.duration() * (1 + 1e-12)) << "trial " << trial;
    for (size_t k = 1; k + 1 < plan.waypoints.size(); ++k) {
      via_points += 1;
      passed += blended.passes_through(k);
    }
    stop_total += stopping.duration();
    blend_total += blended.duration();
  }
  RecordProperty("blended_over_stopping", std::to_string(blend_total / stop_total));
  RecordProperty("via_points_passed", std::to_string(passed) + " of " + std::to_string(via_points));
  std::printf("blended / stopping total time %.4f; %d of %d via points passed through\n",
              blend_total / stop_total, passed, via_points);
  EXPECT_LT(blend_total, stop_total);
}

// [SECTION] The run timing itself

TEST(BlendedRun, EveryBlendFitsItsRoom) {
  std::mt19937_64 rng(43);
  const RobotModelPtr model = test::puma560();
  std::uniform_int_distribution<int> count(3, 12);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<Eigen::VectorXd> points;
    const int n = count(rng);
    for (int i = 0; i < n; ++i) points.push_back(test::random_configuration(*model, rng));
    const std::vector<double> min_durations(static_cast<size_t>(n - 1), 0.0);
    const BlendedRun run = time_blended_run(points, min_durations, model->max_velocities(),
                                            model->max_accelerations());
    const auto& T = run.segment_durations;
    const auto& b = run.blend_durations;
    ASSERT_EQ(b.size(), T.size() + 1);
    for (size_t k = 0; k < b.size(); ++k) {
      if (k > 0) {
        ASSERT_LE(b[k], T[k - 1]) << trial << " " << k;
      }
      if (k < T.size()) {
        ASSERT_LE(b[k], T[k]) << trial << " " << k;
      }
    }
    EXPECT_LE(run.repair_rounds, kMaxRepairRounds);
  }
}

}  // namespace
}  // namespace telear::core
