#include "telear/core/trajectory.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "telear/core/angles.hpp"
#include "telear/core/joint_limits.hpp"
#include "telear/core/trapezoidal_profile.hpp"
#include "test_util/test_util.hpp"

namespace telear::core {
namespace {

using ::testing::HasSubstr;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

using test::deg;

// [SECTION] The normalized trapezoid

TEST(TrapezoidalProfile, CruisesWhenTheRampsLeaveRoom) {
  // alpha = 1 s at full speed, beta = 0.25 s^2: ramps of 0.25 s, cruise at s' = 1.
  const TrapezoidalProfile p = TrapezoidalProfile::Fastest(1.0, 0.25);
  EXPECT_DOUBLE_EQ(p.duration, 1.25);
  EXPECT_DOUBLE_EQ(p.ramp, 0.25);
  EXPECT_DOUBLE_EQ(p.peak_rate, 1.0);
  EXPECT_DOUBLE_EQ(p.acceleration, 4.0);
}

TEST(TrapezoidalProfile, IsATriangleWhenTheCruiseSpeedIsNotReached) {
  const TrapezoidalProfile p = TrapezoidalProfile::Fastest(0.1, 1.0);
  EXPECT_DOUBLE_EQ(p.duration, 2.0);
  EXPECT_DOUBLE_EQ(p.ramp, 1.0);
  EXPECT_DOUBLE_EQ(p.peak_rate, 1.0);
  EXPECT_DOUBLE_EQ(p.acceleration, 1.0);
  EXPECT_LE(p.peak_rate, 1.0 / 0.1);
}

TEST(TrapezoidalProfile, StretchedKeepsTheAccelerationAndLowersTheCruise) {
  const TrapezoidalProfile p = TrapezoidalProfile::Fastest(1.0, 0.25, 3.0);
  EXPECT_DOUBLE_EQ(p.duration, 3.0);
  EXPECT_NEAR(p.acceleration, 4.0, 1e-12);
  EXPECT_LT(p.peak_rate, 1.0);
  // The profile still covers s = 0..1: area = peak * (T - ramp).
  EXPECT_NEAR(p.peak_rate * (p.duration - p.ramp), 1.0, 1e-12);
}

TEST(TrapezoidalProfile, SampleIsContinuousAndExactAtTheEnds) {
  const TrapezoidalProfile p = TrapezoidalProfile::Fastest(0.7, 0.2, 1.5);
  double s, sd, sdd;
  p.sample(0.0, s, sd, sdd);
  EXPECT_EQ(s, 0.0);
  EXPECT_EQ(sd, 0.0);
  p.sample(p.duration, s, sd, sdd);
  EXPECT_EQ(s, 1.0);
  EXPECT_EQ(sd, 0.0);
  double previous = 0.0;
  const double dt = 1e-5;
  for (double t = dt; t <= p.duration; t += dt) {
    p.sample(t, s, sd, sdd);
    EXPECT_LE(std::abs(s - previous), p.peak_rate * dt * (1 + 1e-9));
    EXPECT_GE(s, previous);  // monotone
    previous = s;
  }
}

TEST(TrapezoidalProfile, NoMotionRestsForTheMinimumDuration) {
  const TrapezoidalProfile p = TrapezoidalProfile::Fastest(0.0, 0.0, 2.0);
  EXPECT_EQ(p.duration, 2.0);
  double s, sd, sdd;
  p.sample(1.0, s, sd, sdd);
  EXPECT_EQ(s, 0.0);
  EXPECT_EQ(sd, 0.0);
  EXPECT_EQ(sdd, 0.0);
}

// [SECTION] Trajectories on the PUMA

class PumaTrajectory : public ::testing::Test {
 protected:
  RobotModelPtr model = test::puma560();

  std::vector<JointWaypoint> random_waypoints(std::mt19937_64& rng, int count) const {
    std::vector<JointWaypoint> waypoints;
    for (int i = 0; i < count; ++i) waypoints.push_back({test::random_configuration(*model, rng)});
    return waypoints;
  }

  Trajectory make(std::vector<JointWaypoint> waypoints, const TrajectoryOptions& options = {}) {
    auto trajectory = Trajectory::create(*model, std::move(waypoints), options);
    EXPECT_TRUE(trajectory.ok()) << trajectory.error().message;
    return *trajectory;
  }
};

TEST_F(PumaTrajectory, LimitsHoldAtDenseSamples) {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const Trajectory traj = make(random_waypoints(rng, 4));
    Eigen::VectorXd q, qd, qdd;
    for (double t = 0.0; t <= traj.duration(); t += 1e-3) {
      traj.sample(t, q, &qd, &qdd);
      ASSERT_TRUE(within_limits(*model, q)) << "t = " << t;
      for (int j = 0; j < 6; ++j) {
        ASSERT_LE(std::abs(qd[j]), model->max_velocities()[j] * (1 + 1e-12)) << j << " " << t;
        ASSERT_LE(std::abs(qdd[j]), model->max_accelerations()[j] * (1 + 1e-12)) << j << " " << t;
      }
    }
  }
}

TEST_F(PumaTrajectory, TheSlowestJointSetsEachSegmentsDuration) {
  // Each segment is as short as the limits allow: some joint reaches its max velocity or,
  // in a triangle profile, spends the whole segment at its max acceleration.
  std::mt19937_64 rng(11);
  const Trajectory traj = make(random_waypoints(rng, 6));
  for (size_t k = 0; k + 1 < traj.waypoints().size(); ++k) {
    const double t0 = traj.waypoint_times()[k];
    const double T = traj.waypoint_times()[k + 1] - t0;
    const TrajectoryPoint first_ramp = traj.sample(t0 + 1e-9);
    const TrajectoryPoint middle = traj.sample(t0 + 0.5 * T);
    const double accel_ratio =
        (first_ramp.qdd.cwiseAbs().array() / model->max_accelerations().array()).maxCoeff();
    const double speed_ratio =
        (middle.qd.cwiseAbs().array() / model->max_velocities().array()).maxCoeff();
    EXPECT_NEAR(accel_ratio, 1.0, 1e-9) << "segment " << k;
    const TrapezoidalProfile& p = traj.segment_profiles()[k];
    if (p.ramp < 0.5 * T - 1e-12) {
      EXPECT_NEAR(speed_ratio, 1.0, 1e-9) << "segment " << k;
    } else {
      EXPECT_LE(speed_ratio, 1.0 + 1e-12) << "segment " << k;
    }
  }
}

TEST_F(PumaTrajectory, OneJointAloneMovesInItsOwnMinimumTime) {
  // Joint 1 moves 90 deg at 80 deg/s and 480 deg/s^2: 90 / 80 + 80 / 480 = 1.2917 s.
  const Trajectory traj = make({{deg({0, 0, 0, 0, 0, 0})}, {deg({90, 0, 0, 0, 0, 0})}});
  EXPECT_NEAR(traj.duration(), 90.0 / 80.0 + 80.0 / 480.0, 1e-12);
  // Joint 5 moves 10 deg at 1320 deg/s^2 (a triangle): 2 sqrt(10 / 1320) s.
  const Trajectory small = make({{deg({0, 0, 0, 0, 0, 0})}, {deg({0, 0, 0, 0, 10, 0})}});
  EXPECT_NEAR(small.duration(), 2.0 * std::sqrt(10.0 / 1320.0), 1e-12);
}

TEST_F(PumaTrajectory, JointsAreSynchronizedOnTheStraightJointSpaceLine) {
  std::mt19937_64 rng(3);
  const Trajectory traj = make(random_waypoints(rng, 3));
  for (size_t k = 0; k + 1 < traj.waypoints().size(); ++k) {
    const Eigen::VectorXd& q0 = traj.waypoints()[k].q;
    const Eigen::VectorXd D = traj.waypoints()[k + 1].q - q0;
    const double t0 = traj.waypoint_times()[k];
    const double T = traj.waypoint_times()[k + 1] - t0;
    for (double f : {0.01, 0.2, 0.5, 0.8, 0.99}) {
      const TrajectoryPoint p = traj.sample(t0 + f * T);
      // Every joint has covered the same fraction of its displacement...
      const Eigen::ArrayXd fraction = (p.q - q0).array() / D.array();
      EXPECT_LT(fraction.maxCoeff() - fraction.minCoeff(), 1e-9) << "segment " << k << " " << f;
      // ...and every joint is still moving: none finishes early.
      EXPECT_GT((p.qd.array() / D.array()).minCoeff(), 0.0);
    }
  }
}

TEST_F(PumaTrajectory, PositionAndVelocityAreContinuous) {
  std::mt19937_64 rng(5);
  const Trajectory traj = make(random_waypoints(rng, 4));
  const double h = 1e-6;
  for (double t = 0.0; t <= traj.duration(); t += 0.003) {
    const TrajectoryPoint before = traj.sample(t - h);
    const TrajectoryPoint here = traj.sample(t);
    const TrajectoryPoint after = traj.sample(t + h);
    const Eigen::VectorXd central = (after.q - before.q) / (2 * h);
    // Velocity matches the derivative of position (the acceleration jumps, so allow a*h).
    ASSERT_LT((central - here.qd).cwiseAbs().maxCoeff(), 1e-3) << t;
    ASSERT_LT((after.qd - before.qd).cwiseAbs().maxCoeff(),
              2 * h * model->max_accelerations().maxCoeff() * (1 + 1e-9))
        << t;
  }
}

TEST_F(PumaTrajectory, PassesExactlyThroughEachWaypointAtRest) {
  std::mt19937_64 rng(9);
  const Trajectory traj = make(random_waypoints(rng, 5));
  for (size_t k = 0; k < traj.waypoints().size(); ++k) {
    const TrajectoryPoint p = traj.sample(traj.waypoint_times()[k]);
    EXPECT_EQ(p.q, traj.waypoints()[k].q) << "waypoint " << k;
    EXPECT_EQ(p.qd, Eigen::VectorXd::Zero(6)) << "waypoint " << k;
  }
  EXPECT_EQ(traj.waypoint_times().front(), 0.0);
  EXPECT_EQ(traj.waypoint_times().back(), traj.duration());
}

TEST_F(PumaTrajectory, SamplesOutsideTheTimeRangeAreClampedAtRest) {
  std::mt19937_64 rng(13);
  const Trajectory traj = make(random_waypoints(rng, 3));
  for (double t : {-5.0, -1e-9, -std::numeric_limits<double>::infinity()}) {
    const TrajectoryPoint p = traj.sample(t);
    EXPECT_EQ(p.q, traj.waypoints().front().q);
    EXPECT_EQ(p.qd, Eigen::VectorXd::Zero(6));
    EXPECT_EQ(p.qdd, Eigen::VectorXd::Zero(6));
  }
  for (double t :
       {traj.duration() + 1e-9, traj.duration() + 100.0, std::numeric_limits<double>::infinity()}) {
    const TrajectoryPoint p = traj.sample(t);
    EXPECT_EQ(p.q, traj.waypoints().back().q);
    EXPECT_EQ(p.qd, Eigen::VectorXd::Zero(6));
    EXPECT_EQ(p.qdd, Eigen::VectorXd::Zero(6));
  }
}

TEST_F(PumaTrajectory, MinimumDurationStretchesASegment) {
  const Trajectory fast = make({{deg({0, 0, 0, 0, 0, 0})}, {deg({30, 0, 0, 0, 0, 0})}});
  JointWaypoint slow_end{deg({30, 0, 0, 0, 0, 0})};
  slow_end.min_duration = 5.0;
  const Trajectory slow = make({{deg({0, 0, 0, 0, 0, 0})}, slow_end});
  EXPECT_LT(fast.duration(), 5.0);
  EXPECT_DOUBLE_EQ(slow.duration(), 5.0);
  const TrajectoryPoint middle = slow.sample(2.5);
  EXPECT_LT(std::abs(middle.qd[0]), model->max_velocities()[0]);
  EXPECT_NEAR(middle.q[0], radians_from_degrees(15.0), 1e-12);  // symmetric profile
}

TEST_F(PumaTrajectory, SpeedScalingSlowsEveryJoint) {
  std::mt19937_64 rng(17);
  const auto waypoints = random_waypoints(rng, 3);
  const Trajectory full = make(waypoints);
  const Trajectory half = make(waypoints, {.velocity_scale = 0.5, .acceleration_scale = 0.25});
  // Halving v and quartering a doubles every time exactly.
  EXPECT_NEAR(half.duration(), 2.0 * full.duration(), 1e-9);
  for (double t = 0.0; t <= half.duration(); t += 0.01) {
    const TrajectoryPoint p = half.sample(t);
    ASSERT_LE((p.qd.cwiseAbs().array() / model->max_velocities().array()).maxCoeff(), 0.5 + 1e-12);
  }
}

TEST_F(PumaTrajectory, OneWaypointAndRepeatedWaypointsAreDwells) {
  const Trajectory one = make({{deg({10, 20, 30, 0, 0, 0})}});
  EXPECT_EQ(one.duration(), 0.0);
  EXPECT_EQ(one.sample(0.0).q, deg({10, 20, 30, 0, 0, 0}));

  JointWaypoint grip{deg({10, 20, 30, 0, 0, 0})};
  grip.gripper = 0.0;
  JointWaypoint dwell{deg({10, 20, 30, 0, 0, 0})};
  dwell.min_duration = 0.5;
  JointWaypoint no_wait{deg({10, 20, 30, 0, 0, 0})};  // zero-duration segment
  JointWaypoint start{deg({0, 0, 0, 0, 0, 0})};
  start.gripper = 1.0;
  const Trajectory traj = make({start, grip, dwell, no_wait});
  const double arrive = traj.waypoint_times()[1];
  EXPECT_DOUBLE_EQ(traj.duration(), arrive + 0.5);
  EXPECT_EQ(traj.sample(arrive + 0.25).q, deg({10, 20, 30, 0, 0, 0}));
  EXPECT_FALSE(traj.gripper_at(-1.0).has_value());
  EXPECT_EQ(traj.gripper_at(0.0), 1.0);
  EXPECT_EQ(traj.gripper_at(arrive - 1e-9), 1.0);
  EXPECT_EQ(traj.gripper_at(arrive), 0.0);
  ASSERT_EQ(traj.gripper_events().size(), 2u);
  EXPECT_EQ(traj.gripper_events()[1].time, arrive);
}

// [SECTION] Sampled form

TEST_F(PumaTrajectory, SampledFormHitsEveryWaypointAndPassesValidation) {
  std::mt19937_64 rng(19);
  auto waypoints = random_waypoints(rng, 4);
  waypoints[2].gripper = 0.3;
  const Trajectory traj = make(waypoints);
  for (double rate : {10.0, 100.0, 1000.0}) {
    const auto sampled = traj.sampled(rate);
    ASSERT_TRUE(sampled.ok()) << sampled.error().message;
    const TimedWaypoints& w = *sampled;
    ASSERT_EQ(w.times.size(), w.q.size());
    EXPECT_EQ(w.times.front(), 0.0);
    EXPECT_EQ(w.times.back(), traj.duration());
    for (size_t i = 1; i < w.times.size(); ++i) {
      ASSERT_GT(w.times[i], w.times[i - 1]);
      ASSERT_LE(w.times[i] - w.times[i - 1], 1.0 / rate * (1 + 1e-9));
    }
    for (size_t k = 0; k < waypoints.size(); ++k) {
      const auto at = std::find(w.times.begin(), w.times.end(), traj.waypoint_times()[k]);
      ASSERT_NE(at, w.times.end()) << "waypoint " << k << " at " << rate << " Hz";
      EXPECT_EQ(w.q[static_cast<size_t>(at - w.times.begin())], waypoints[k].q);
    }
    for (size_t i = 0; i < w.times.size(); i += 7) {
      EXPECT_LT((w.q[i] - traj.sample(w.times[i]).q).cwiseAbs().maxCoeff(), 1e-15);
    }
    ASSERT_EQ(w.gripper.size(), 1u);
    EXPECT_EQ(w.gripper[0].time, traj.waypoint_times()[2]);
    EXPECT_EQ(w.gripper[0].opening, 0.3);
    const Status valid = validate_timed_waypoints(*model, w);
    EXPECT_TRUE(valid.ok()) << valid.error().message;
  }
}

TEST_F(PumaTrajectory, SampledFormOfDwellsHasStrictlyIncreasingTimes) {
  JointWaypoint a{deg({0, 0, 0, 0, 0, 0})};
  JointWaypoint b{deg({0, 0, 0, 0, 0, 0})};  // zero-duration segment
  JointWaypoint c{deg({0, 0, 0, 0, 0, 0})};
  c.min_duration = 0.05;
  JointWaypoint d{deg({5, 0, 0, 0, 0, 0})};
  const auto w = make({a, b, c, d}).sampled(100.0);
  ASSERT_TRUE(w.ok()) << w.error().message;
  for (size_t i = 1; i < w->times.size(); ++i) ASSERT_GT(w->times[i], w->times[i - 1]);
  EXPECT_EQ(w->q.back(), d.q);
  EXPECT_TRUE(validate_timed_waypoints(*model, *w).ok());
}

TEST_F(PumaTrajectory, SampledRejectsABadRateOrTooManySamples) {
  const Trajectory traj = make({{deg({0, 0, 0, 0, 0, 0})}, {deg({90, 0, 0, 0, 0, 0})}});
  for (double rate : {0.0, -10.0, kNaN, std::numeric_limits<double>::infinity()}) {
    const auto w = traj.sampled(rate);
    ASSERT_FALSE(w.ok());
    EXPECT_THAT(w.error().message, HasSubstr("sample rate must be a positive finite number of Hz"));
  }
  const auto w = traj.sampled(100.0, 100);
  ASSERT_FALSE(w.ok());
  EXPECT_EQ(w.error().message,
            "sampling the 1.29167 s trajectory at 100 Hz needs 131 samples, more than the "
            "maximum of 100");
}

// [SECTION] Validation of waypoints

class WaypointValidation : public PumaTrajectory {
 protected:
  std::string rejection(const std::vector<JointWaypoint>& waypoints,
                        const TrajectoryOptions& options = {}) {
    const auto trajectory = Trajectory::create(*model, waypoints, options);
    EXPECT_FALSE(trajectory.ok());
    const Status status = validate_waypoints(*model, waypoints, options);
    EXPECT_FALSE(status.ok());
    if (trajectory.ok() || status.ok()) return {};
    EXPECT_EQ(trajectory.error().message, status.error().message);
    return status.error().message;
  }
  const Eigen::VectorXd home = deg({0, 0, 0, 0, 0, 0});
};

TEST_F(WaypointValidation, RejectsAnEmptyOrOversizedList) {
  EXPECT_EQ(rejection({}), "a trajectory needs at least one waypoint, got none");
  EXPECT_EQ(rejection({{home}, {home}, {home}}, {.max_waypoints = 2}),
            "trajectory has 3 waypoints, more than the maximum of 2");
}

TEST_F(WaypointValidation, RejectsBadJointVectors) {
  EXPECT_EQ(rejection({{home}, {Eigen::VectorXd::Zero(5)}}),
            "waypoint[1]: expected 6 joint values, got 5");
  Eigen::VectorXd nan = home;
  nan[3] = kNaN;
  EXPECT_EQ(rejection({{nan}}),
            "waypoint[0]: joint 4 (wrist_roll) value is not a finite number: nan");
  EXPECT_EQ(rejection({{home}, {home}, {deg({0, 120, 0, 0, 0, 0})}}),
            "waypoint[2]: joint 2 (shoulder) would be at 120.00 deg, beyond its upper limit of "
            "110.00 deg");
  EXPECT_EQ(rejection({{deg({0, 0, 0, 0, -101, 0})}}),
            "waypoint[0]: joint 5 (wrist_bend) would be at -101.00 deg, beyond its lower limit of "
            "-100.00 deg");
}

TEST_F(WaypointValidation, RejectsBadDurationsAndGripperOpenings) {
  JointWaypoint w{home};
  w.min_duration = kNaN;
  EXPECT_EQ(rejection({{home}, w}), "waypoint[1]: minimum duration is not a finite number: nan");
  w.min_duration = -0.5;
  EXPECT_EQ(rejection({{home}, w}), "waypoint[1]: minimum duration -0.5 s is negative");
  w.min_duration = 7200.0;
  EXPECT_EQ(rejection({{home}, w}),
            "waypoint[1]: minimum duration 7200 s exceeds the maximum of 3600 s");
  JointWaypoint g{home};
  g.gripper = 1.5;
  EXPECT_EQ(rejection({g}),
            "waypoint[0]: gripper opening 1.5 is outside [0, 1] (0 closed, 1 open)");
  g.gripper = kNaN;
  EXPECT_EQ(rejection({g}),
            "waypoint[0]: gripper opening nan is outside [0, 1] (0 closed, 1 open)");
}

TEST_F(WaypointValidation, RejectsBadOptions) {
  EXPECT_EQ(rejection({{home}}, {.velocity_scale = 0.0}),
            "velocity_scale must be in [0.001, 1], got 0");
  EXPECT_EQ(rejection({{home}}, {.acceleration_scale = 1.5}),
            "acceleration_scale must be in [0.001, 1], got 1.5");
  // fuzz/crashes/robot_rpc/crash-9689f06e...: scales of 1e-314 and 1e-312 gave the trajectory
  // a NaN duration, which plan_hash then converted to an integer (undefined behaviour).
  EXPECT_EQ(rejection({{home}}, {.velocity_scale = 1.85674631709461e-314}),
            "velocity_scale must be in [0.001, 1], got 1.85675e-314");
  EXPECT_EQ(rejection({{home}}, {.acceleration_scale = 0.000999}),
            "acceleration_scale must be in [0.001, 1], got 0.000999");
  EXPECT_TRUE(validate_waypoints(*model, {{home}}, {.velocity_scale = 0.001}));
  EXPECT_EQ(rejection({{home}}, {.max_waypoints = 0}), "max_waypoints must be at least 1, got 0");
  EXPECT_EQ(rejection({{home}}, {.max_segment_duration = kNaN}),
            "max_segment_duration must be a non-negative finite number, got nan");
}

// [SECTION] Validation of timed waypoints from an untrusted sender

class TimedValidation : public PumaTrajectory {
 protected:
  // A valid message: joint 1 from 0 to 1 deg, stretched to 1 s, at 100 Hz (t = 0, 0.01, ...).
  TimedWaypoints valid() const {
    JointWaypoint end{deg({1, 0, 0, 0, 0, 0})};
    end.min_duration = 1.0;
    const Trajectory traj = *Trajectory::create(*model, {{deg({0, 0, 0, 0, 0, 0})}, end});
    return *traj.sampled(100.0);
  }
  std::string rejection(const TimedWaypoints& w, const TimedWaypointsLimits& limits = {}) {
    const Status status = validate_timed_waypoints(*model, w, limits);
    EXPECT_FALSE(status.ok());
    return status.ok() ? std::string() : status.error().message;
  }
};

TEST_F(TimedValidation, TheValidMessagePasses) {
  const Status status = validate_timed_waypoints(*model, valid());
  EXPECT_TRUE(status.ok()) << status.error().message;
  // A single sample is a valid "stay here" message.
  EXPECT_TRUE(validate_timed_waypoints(*model, {{0.5}, {deg({0, 0, 0, 0, 0, 0})}, {}}).ok());
}

TEST_F(TimedValidation, RejectsEmptyOversizedAndMismatchedMessages) {
  EXPECT_EQ(rejection({}), "timed waypoints: no samples");
  TimedWaypoints w = valid();
  const size_t n = w.times.size();
  EXPECT_EQ(rejection(w, {.max_samples = 5}),
            "timed waypoints: " + std::to_string(n) + " samples, more than the maximum of 5");
  w.q.pop_back();
  EXPECT_EQ(rejection(w), "timed waypoints: " + std::to_string(n) + " times but " +
                              std::to_string(n - 1) + " joint vectors");
}

TEST_F(TimedValidation, RejectsBadTimes) {
  TimedWaypoints w = valid();
  w.times[3] = kNaN;
  EXPECT_EQ(rejection(w), "sample[3]: time is not a finite number: nan");
  w = valid();
  w.times[0] = -0.01;
  EXPECT_EQ(rejection(w), "sample[0]: time -0.01 s is negative (times start at 0 or later)");
  w = valid();
  w.times[4] = w.times[3];
  EXPECT_EQ(rejection(w),
            "sample[4]: time 0.03 s is not after the previous sample's 0.03 s (times must "
            "strictly increase)");
  w = valid();
  std::swap(w.times[4], w.times[5]);
  EXPECT_THAT(rejection(w), HasSubstr("sample[5]: time 0.04 s is not after the previous"));
}

TEST_F(TimedValidation, RejectsBadJointVectors) {
  TimedWaypoints w = valid();
  w.q[2] = Eigen::VectorXd::Zero(7);
  EXPECT_EQ(rejection(w), "sample[2]: expected 6 joint values, got 7");
  w = valid();
  w.q[2][5] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(rejection(w), "sample[2]: joint 6 (wrist_swivel) value is not a finite number: inf");
  w = valid();
  w.q[2][2] = radians_from_degrees(-140.0);
  EXPECT_EQ(rejection(w),
            "sample[2]: joint 3 (elbow) would be at -140.00 deg, beyond its lower limit of "
            "-135.00 deg");
}

TEST_F(TimedValidation, RejectsExcessiveVelocity) {
  // Joint 2 jumps 1 deg in 10 ms: 100 deg/s against a limit of 70 deg/s.
  TimedWaypoints w{{0.0, 1.0, 1.01, 2.0}, {}, {}};
  w.q = {deg({0, 0, 0, 0, 0, 0}), deg({0, 0, 0, 0, 0, 0}), deg({0, 1, 0, 0, 0, 0}),
         deg({0, 1, 0, 0, 0, 0})};
  EXPECT_EQ(rejection(w),
            "sample[1] to sample[2] (t = 1 s to 1.01 s): joint 2 (shoulder) moves at 100.00 deg/s, "
            "beyond its max velocity of 70.00 deg/s");
}

TEST_F(TimedValidation, RejectsExcessiveAcceleration) {
  // Joint 5 moves 1 deg in 10 ms (100 deg/s, within its 220 deg/s) right after resting.
  TimedWaypoints w{{0.0, 0.1, 0.11, 0.12, 0.3}, {}, {}};
  w.q = {deg({0, 0, 0, 0, 0, 0}), deg({0, 0, 0, 0, 0, 0}), deg({0, 0, 0, 0, 0, 0}),
         deg({0, 0, 0, 0, 1, 0}), deg({0, 0, 0, 0, 1, 0})};
  // At sample[2] the mean velocity goes from 0 to 100 deg/s over 10 ms: 10000 deg/s^2.
  EXPECT_EQ(rejection(w),
            "sample[2] (t = 0.11 s): joint 5 (wrist_bend) accelerates at 10000.00 deg/s^2, beyond "
            "its max acceleration of 1320.00 deg/s^2");
}

TEST_F(TimedValidation, RequiresStartingAndEndingAtRest) {
  // Cruising from the first sample: 10 deg/s from rest over 0.01 s / 2 = 2000 deg/s^2.
  TimedWaypoints start{{0.0, 0.01, 1.0}, {}, {}};
  start.q = {deg({0, 0, 0, 0, 0, 0}), deg({0, 0, 0, 0, 0.1, 0}), deg({0, 0, 0, 0, 0.1, 0})};
  EXPECT_EQ(rejection(start),
            "sample[0] (t = 0 s, starting from rest): joint 5 (wrist_bend) accelerates at "
            "2000.00 deg/s^2, beyond its max acceleration of 1320.00 deg/s^2");
  TimedWaypoints end{{0.0, 0.99, 1.0}, {}, {}};
  end.q = {deg({0, 0, 0, 0, 0, 0}), deg({0, 0, 0, 0, 0, 0}), deg({0, 0, 0, 0, 0.1, 0})};
  EXPECT_THAT(rejection(end), HasSubstr("sample[2] (t = 1 s, ending at rest): joint 5 "
                                        "(wrist_bend) accelerates at -2000.00 deg/s^2"));
}

TEST_F(TimedValidation, ToleratesRoundingButNotMore) {
  // Exactly at the velocity limit passes; 1e-6 relative above is tolerated; 1e-5 is not.
  const double v = model->max_velocities()[3];
  auto check = [&](double factor) {
    TimedWaypoints w{{0.0, 10.0, 11.0, 21.0}, {}, {}};
    w.q = {Eigen::VectorXd::Zero(6), Eigen::VectorXd::Zero(6), Eigen::VectorXd::Zero(6),
           Eigen::VectorXd::Zero(6)};
    w.q[2][3] = w.q[3][3] = v * factor;  // over the 1 s interval
    return validate_timed_waypoints(*model, w, {.relative_tolerance = 1e-6});
  };
  // Reaching that speed over a mean interval of 5.5 s needs v / 5.5 s^2, far below the
  // joint's acceleration limit, so only the velocity is at stake.
  EXPECT_TRUE(check(1.0).ok());
  EXPECT_TRUE(check(1.0 + 5e-7).ok());
  const Status over = check(1.0 + 1e-5);
  ASSERT_FALSE(over.ok());
  EXPECT_THAT(over.error().message, HasSubstr("joint 4 (wrist_roll) moves at 220.00 deg/s"));
}

TEST_F(TimedValidation, RejectsBadGripperEvents) {
  TimedWaypoints w = valid();
  const double end = w.times.back();
  w.gripper = {{kNaN, 0.5}};
  EXPECT_EQ(rejection(w), "gripper event[0]: time is not a finite number: nan");
  w.gripper = {{0.0, 1.0}, {end + 1.0, 0.5}};
  EXPECT_EQ(rejection(w), "gripper event[1]: time 2 s is outside the samples' span 0 s to 1 s");
  w.gripper = {{0.05, 1.0}, {0.02, 0.5}};
  EXPECT_EQ(rejection(w), "gripper event[1]: time 0.02 s is before the previous event's 0.05 s");
  w.gripper = {{0.05, -0.1}};
  EXPECT_EQ(rejection(w), "gripper event[0]: opening -0.1 is outside [0, 1] (0 closed, 1 open)");
}

}  // namespace
}  // namespace telear::core
