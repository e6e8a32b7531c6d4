#pragma once
// Angles are radians everywhere inside telear; degrees exist only at the CLI, UI and
// configuration-file edges, converted once with these functions.

#include <cmath>
#include <numbers>

namespace telear::core {

constexpr double radians_from_degrees(double degrees) {
  return degrees * std::numbers::pi / 180.0;
}
constexpr double degrees_from_radians(double radians) {
  return radians * 180.0 / std::numbers::pi;
}

// Wraps an angle to (-pi, pi].
inline double wrap_to_pi(double angle) {
  double wrapped = std::remainder(angle, 2.0 * std::numbers::pi);
  if (wrapped <= -std::numbers::pi) wrapped += 2.0 * std::numbers::pi;
  return wrapped;
}

// wrap_to_pi for angles within a few turns (the closed-form IK's): a subtraction or two
// instead of std::remainder, which would take a tenth of a solver's time.
inline double wrap_small_angle(double angle) {
  if (std::abs(angle) > 8.0 * std::numbers::pi) return wrap_to_pi(angle);  // a huge DH offset
  while (angle > std::numbers::pi) angle -= 2.0 * std::numbers::pi;
  while (angle <= -std::numbers::pi) angle += 2.0 * std::numbers::pi;
  return angle;
}

}  // namespace telear::core
