#include "telear/sim/joint_motion.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "telear/sim/sim_clock.hpp"

namespace telear::sim {
namespace {

constexpr double kDt = 0.001;
constexpr double kInf = std::numeric_limits<double>::infinity();

// Runs step_toward until the joint arrives (or max_steps), checking every period's velocity
// and velocity change against the limits; returns the number of periods taken.
int run_to_target(JointMotion& m, double target, const JointStepLimits& l, int max_steps) {
  for (int k = 0; k < max_steps; ++k) {
    const JointMotion next = step_toward(m, target, l, kDt);
    EXPECT_LE(std::abs(next.qd), l.max_velocity * (1 + 1e-12)) << "period " << k;
    EXPECT_LE(std::abs(next.qd - m.qd), l.max_acceleration * kDt * (1 + 1e-9)) << "period " << k;
    EXPECT_GE(next.q, l.lower);
    EXPECT_LE(next.q, l.upper);
    m = next;
    if (arrived(m, target)) return k + 1;
  }
  return -1;
}

TEST(BrakingSpeed, BrakingFromItCoversExactlyTheDistance) {
  const double a = 5.0;
  for (double d : {0.3e-6, 2e-6, 1e-3, 0.0123, 0.5, 2.0}) {
    double v = braking_speed(d, a, kDt);
    double covered = 0.0;
    int periods = 0;
    while (v > 0.0 && periods < 100000) {
      covered += v * kDt;
      v = std::max(0.0, v - a * kDt);
      ++periods;
    }
    EXPECT_NEAR(covered, d, 1e-12 * std::max(1.0, d)) << "distance " << d;
  }
  EXPECT_EQ(braking_speed(0.0, a, kDt), 0.0);
  EXPECT_EQ(braking_speed(-1.0, a, kDt), 0.0);
  EXPECT_EQ(braking_speed(kInf, a, kDt), kInf);
  // Far from the point the curve approaches the continuous sqrt(2 a d) from below.
  EXPECT_NEAR(braking_speed(1.0, a, kDt), std::sqrt(2.0 * a), 0.01);
  EXPECT_LT(braking_speed(1.0, a, kDt), std::sqrt(2.0 * a));
}

TEST(StepToward, LandsExactlyOnTheTargetWithinTheLimits) {
  const JointStepLimits l{-3.0, 3.0, 1.2, 5.0};
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> position(-2.9, 2.9), velocity(-1.2, 1.2);
  for (int trial = 0; trial < 50; ++trial) {
    // Start anywhere, moving either way at any speed the position limits allow.
    JointMotion m{position(rng), 0.0};
    m.qd = std::clamp(velocity(rng), -braking_speed(m.q - l.lower, l.max_acceleration, kDt),
                      braking_speed(l.upper - m.q, l.max_acceleration, kDt));
    const double target = position(rng);
    const int periods = run_to_target(m, target, l, 20000);
    ASSERT_GT(periods, 0) << "trial " << trial << " did not arrive";
    EXPECT_EQ(m.q, target);
    EXPECT_EQ(m.qd, 0.0);
  }
}

TEST(StepToward, FromRestTakesTheTrapezoidsTimeToWithinAFewPeriods) {
  // 1 rad at v = 1, a = 4: ramps of 0.25 s, total 1.25 s.
  const JointStepLimits l{-kInf, kInf, 1.0, 4.0};
  JointMotion m{0.0, 0.0};
  const int periods = run_to_target(m, 1.0, l, 5000);
  EXPECT_NEAR(periods * kDt, 1.25, 3 * kDt);
}

TEST(StepVelocity, BrakesOntoAJointLimitWithoutPassingIt) {
  const JointStepLimits l{-1.0, 1.0, 2.0, 3.0};
  JointMotion m{0.0, 0.0};
  for (int k = 0; k < 3000; ++k) {
    const JointMotion next = step_velocity(m, 2.0, l.max_acceleration, l, kDt);
    ASSERT_LE(next.q, l.upper) << "period " << k;
    EXPECT_LE(std::abs(next.qd - m.qd), l.max_acceleration * kDt * (1 + 1e-9));
    m = next;
  }
  EXPECT_NEAR(m.q, l.upper, 1e-12);
  EXPECT_EQ(m.qd, 0.0);
  // Beyond a limit a joint may only move back.
  const JointMotion beyond = step_velocity({1.5, 0.0}, 1.0, 3.0, l, kDt);
  EXPECT_EQ(beyond.qd, 0.0);
  EXPECT_LT(step_velocity({1.5, 0.0}, -1.0, 3.0, l, kDt).qd, 0.0);
}

TEST(StoppingTime, IsTheSlowestJointsSpeedOverItsDeceleration) {
  const Eigen::Vector3d qd(1.0, -2.0, 0.5);
  const Eigen::Vector3d a(4.0, 4.0, 1.0);
  EXPECT_DOUBLE_EQ(stopping_time(qd, a), 0.5);
  EXPECT_DOUBLE_EQ(stopping_time(qd, a, 0.5), 1.0);
  EXPECT_DOUBLE_EQ(worst_case_stopping_time(Eigen::Vector3d(1, 1, 1), a), 1.0);
}

TEST(ManualClock, MovesOnlyWhenAdvanced) {
  ManualClock clock(2.0);
  EXPECT_EQ(clock.now(), 2.0);
  clock.advance(0.5);
  EXPECT_EQ(clock.now(), 2.5);
  clock.set(10.0);
  EXPECT_EQ(clock.now(), 10.0);
}

TEST(SteadyClock, NeverGoesBack) {
  SteadyClock clock;
  const double t1 = clock.now();
  const double t2 = clock.now();
  EXPECT_GE(t1, 0.0);
  EXPECT_GE(t2, t1);
}

}  // namespace
}  // namespace telear::sim
