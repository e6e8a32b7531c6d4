#pragma once
// Internal to lab: seconds elapsed on the steady clock since `start` (the demo's phases and
// timeouts), defined once for the library's sources.

#include <chrono>

namespace telear::lab {

inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace telear::lab
