#pragma once
// Discrete-time motion of one joint within its position, velocity and acceleration limits,
// as the simulated servo integrates it. Every servo period dt the joint's velocity changes by
// at most a dt, then its position moves by (new velocity) dt (semi-implicit Euler). Positions
// and velocities are in the joint's units: rad and rad/s (revolute), m and m/s (prismatic).
//
// Braking curve. A joint that brakes by a dt every period, starting from the speed
// v = w a dt in this period, covers (this period included)
//
//   d = a dt^2 sum_{i=0..m} (w - i) = a dt^2 ((m + 1) w - m (m + 1) / 2),   m = floor(w)
//
// before it is at rest. Inverting it gives the highest speed from which it still stops
// exactly at a point a distance d ahead:
//
//   E = d / (a dt^2),   m = floor((sqrt(1 + 8 E) - 1) / 2),   w = (E + m (m + 1) / 2) / (m + 1)
//
// Riding that curve, the speed drops by exactly a dt per period and the last period covers
// the remainder, so the joint lands on a jog target or a joint limit without overshooting and
// without braking harder than a. (The continuous curve sqrt(2 a d) overshoots by up to a dt^2
// per stop, which at a joint limit would be a limit violation.) Every step below applies the
// curve towards both joint limits as a speed cap: a joint that starts within its limits stays
// within them whatever it is commanded to do.

#include <Eigen/Core>

namespace telear::sim {

struct JointStepLimits {
  double lower = 0.0;  // position limits, may be infinite
  double upper = 0.0;
  double max_velocity = 0.0;      // > 0
  double max_acceleration = 0.0;  // > 0
};

struct JointMotion {
  double q = 0.0;
  double qd = 0.0;
};

// The highest speed (>= 0) from which the joint stops exactly `distance` ahead, braking by
// max_acceleration * dt per period of dt; 0 for distance <= 0, infinity for a huge distance.
double braking_speed(double distance, double max_acceleration, double dt);

// One period of changing the velocity towards `velocity` at up to `acceleration` (<= the
// limit's max_acceleration), the speed capped by max_velocity and by the braking curves of
// both position limits (which may brake at up to max_acceleration).
JointMotion step_velocity(JointMotion state, double velocity, double acceleration,
                          const JointStepLimits& limits, double dt);

// One period of moving towards `target` as fast as the limits allow: accelerate to the speed
// the braking curve of the target allows (at most max_velocity), ride the curve down, and
// arrive at rest exactly on the target. A joint already moving away first brakes and turns.
JointMotion step_toward(JointMotion state, double target, const JointStepLimits& limits, double dt);

// True when the joint rests exactly on target.
inline bool arrived(const JointMotion& state, double target) {
  return state.qd == 0.0 && state.q == target;
}

// The time a controlled stop from joint velocities qd takes when each joint may decelerate at
// deceleration_scale times its max acceleration: max_j |qd_j| / (scale a_j). All joints brake
// over this same time (each at |qd_j| / T), so the arm stays on its current joint-space path.
double stopping_time(const Eigen::VectorXd& qd, const Eigen::VectorXd& max_acceleration,
                     double deceleration_scale = 1.0);

// The longest controlled stop: from every joint at its max velocity.
double worst_case_stopping_time(const Eigen::VectorXd& max_velocity,
                                const Eigen::VectorXd& max_acceleration,
                                double deceleration_scale = 1.0);

}  // namespace telear::sim
