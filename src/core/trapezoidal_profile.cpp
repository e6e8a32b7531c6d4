#include "telear/core/trapezoidal_profile.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace telear::core {

TrapezoidalProfile TrapezoidalProfile::Fastest(double alpha, double beta, double min_duration) {
  assert(alpha >= 0.0 && beta >= 0.0 && min_duration >= 0.0);
  TrapezoidalProfile p;
  if (beta <= 0.0) {  // nothing moves (every displacement is zero)
    p.duration = min_duration;
    return p;
  }
  // Shortest duration: cruise at 1 / alpha when the ramps leave room for it, else a triangle.
  const double fastest = (alpha * alpha >= beta) ? alpha + beta / alpha : 2.0 * std::sqrt(beta);
  const double T = std::max(fastest, min_duration);
  const double discriminant = std::max(0.0, T * T - 4.0 * beta);
  // Rounding may put the ramp a hair beyond T / 2; the triangle is its limit.
  const double ramp = std::min(2.0 * beta / (T + std::sqrt(discriminant)), 0.5 * T);
  p.duration = T;
  p.ramp = ramp;
  p.peak_rate = 1.0 / (T - ramp);
  p.acceleration = p.peak_rate / ramp;
  return p;
}

void TrapezoidalProfile::sample(double t, double& s, double& s_dot, double& s_ddot) const {
  if (peak_rate == 0.0 || t <= 0.0) {
    s = 0.0;
    s_dot = 0.0;
    s_ddot = 0.0;
    return;
  }
  if (t >= duration) {
    s = 1.0;
    s_dot = 0.0;
    s_ddot = 0.0;
    return;
  }
  if (t < ramp) {
    s = 0.5 * acceleration * t * t;
    s_dot = acceleration * t;
    s_ddot = acceleration;
  } else if (t <= duration - ramp) {
    s = peak_rate * (t - 0.5 * ramp);
    s_dot = peak_rate;
    s_ddot = 0.0;
  } else {
    // Measured back from the end so that s reaches exactly 1.
    const double to_go = duration - t;
    s = 1.0 - 0.5 * acceleration * to_go * to_go;
    s_dot = acceleration * to_go;
    s_ddot = -acceleration;
  }
  s = std::clamp(s, 0.0, 1.0);
}

}  // namespace telear::core
