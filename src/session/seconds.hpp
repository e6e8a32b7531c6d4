#pragma once
// Internal to session: a time in seconds as text in messages and reports ("1.250 s"), defined
// once for the library's sources. (Elapsed time is core::seconds_since, core/clock.hpp.)

#include <string>

#include "telear/core/number_format.hpp"

namespace telear::session {

inline std::string seconds(double value) {
  return core::format_fixed(value, 3, "s");
}

}  // namespace telear::session
