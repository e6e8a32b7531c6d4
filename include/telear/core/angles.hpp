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

}  // namespace telear::core
