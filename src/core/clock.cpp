#include "telear/core/clock.hpp"

#include <chrono>

namespace telear::core {

std::int64_t monotonic_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

}  // namespace telear::core
