#include "telear/sim/joint_motion.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace telear::sim {
namespace {

// Below this distance (rad or m) a joint at rest counts as on its target; far below any
// encoder's resolution, it only absorbs the rounding of the last period's q + (d / dt) dt.
constexpr double kArrivalDistance = 1e-12;

}  // namespace

double braking_speed(double distance, double max_acceleration, double dt) {
  assert(max_acceleration > 0.0 && dt > 0.0 && "braking_speed(): a and dt must be positive");
  if (!(distance > 0.0)) return 0.0;
  const double step = max_acceleration * dt;  // speed lost per period
  const double E = distance / (step * dt);
  // Beyond this the speed would exceed any joint's max velocity by orders of magnitude (and
  // sqrt(1 + 8 E) loses its meaning for an infinite distance).
  if (!(E < 1e15)) return std::numeric_limits<double>::infinity();
  const double m = std::floor((std::sqrt(1.0 + 8.0 * E) - 1.0) / 2.0);
  const double w = (E + m * (m + 1.0) / 2.0) / (m + 1.0);
  return w * step;
}

JointMotion step_velocity(JointMotion state, double velocity, double acceleration,
                          const JointStepLimits& limits, double dt) {
  assert(acceleration >= 0.0 && acceleration <= limits.max_acceleration * (1.0 + 1e-12));
  const double a = limits.max_acceleration;
  const double dv = std::clamp(velocity - state.qd, -acceleration * dt, acceleration * dt);
  double v = state.qd + dv;
  // Speed caps: max velocity and the braking curves of both position limits. They may brake
  // harder than `acceleration` (up to the limit's a), never harder than a.
  const double v_high = std::min(limits.max_velocity, braking_speed(limits.upper - state.q, a, dt));
  const double v_low = -std::min(limits.max_velocity, braking_speed(state.q - limits.lower, a, dt));
  v = std::min(v, v_high);
  v = std::max(v, v_low);
  v = std::clamp(v, state.qd - a * dt, state.qd + a * dt);
  double q = state.q + v * dt;
  // The caps land a joint exactly on a limit up to rounding; keep the rounding inside.
  if (state.q <= limits.upper) q = std::min(q, limits.upper);
  if (state.q >= limits.lower) q = std::max(q, limits.lower);
  return {q, v};
}

JointMotion step_toward(JointMotion state, double target, const JointStepLimits& limits,
                        double dt) {
  const double error = target - state.q;
  double velocity = 0.0;
  if (std::abs(error) > kArrivalDistance) {
    velocity = std::copysign(
        std::min(limits.max_velocity, braking_speed(std::abs(error), limits.max_acceleration, dt)),
        error);
  }
  JointMotion next = step_velocity(state, velocity, limits.max_acceleration, limits, dt);
  if (next.qd == 0.0 && std::abs(target - next.q) <= kArrivalDistance) next.q = target;
  return next;
}

double stopping_time(const Eigen::VectorXd& qd, const Eigen::VectorXd& max_acceleration,
                     double deceleration_scale) {
  assert(qd.size() == max_acceleration.size() && deceleration_scale > 0.0);
  double T = 0.0;
  for (Eigen::Index j = 0; j < qd.size(); ++j) {
    T = std::max(T, std::abs(qd[j]) / (deceleration_scale * max_acceleration[j]));
  }
  return T;
}

double worst_case_stopping_time(const Eigen::VectorXd& max_velocity,
                                const Eigen::VectorXd& max_acceleration,
                                double deceleration_scale) {
  return stopping_time(max_velocity, max_acceleration, deceleration_scale);
}

}  // namespace telear::sim
