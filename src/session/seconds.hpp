#pragma once
// Internal to session: time in seconds -- elapsed on the steady clock (the capture loops'
// timeouts) and as text in messages and reports ("1.250 s") -- defined once for the library's
// sources.

#include <chrono>
#include <string>

#include "telear/core/number_format.hpp"

namespace telear::session {

inline double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

inline std::string seconds(double value) {
  return core::format_fixed(value, 3, "s");
}

}  // namespace telear::session
