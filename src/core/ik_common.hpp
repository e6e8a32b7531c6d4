#pragma once
// Internal to core: what the closed-form solvers (ik_analytic.cpp for PUMA-class arms, ik_ur.cpp
// for UR-class arms) and the solver dispatch (inverse_kinematics.cpp) share -- their tolerances
// and the units of their messages -- defined once, so that the library's sources can be
// compiled together (a unity build) without two definitions of one file-local name.

#include <string>

#include "telear/core/angles.hpp"
#include "telear/core/number_format.hpp"

namespace telear::core {

// Joint values this close outside a limit still count as within it (rounding of a solution
// lying on a limit).
inline constexpr double kLimitTolerance = 1e-9;  // rad
// Lengths within this of a reach boundary count as on it (rounding of the target pose).
inline constexpr double kReachTolerance = 1e-10;  // m
// Flags a solution `singular` when the relevant sine or distance is below this.
inline constexpr double kSingularTolerance = 1e-6;  // 1 (a sine), rad or m

// Lengths and angles in the solvers' messages: "0.8641 m", "12.50 deg".
inline std::string format_length(double metres) {
  return format_fixed(metres, 4, "m");
}
inline std::string format_angle(double radians) {
  return format_fixed(degrees_from_radians(radians), 2, "deg");
}

}  // namespace telear::core
