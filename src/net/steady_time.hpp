#pragma once
// Internal to net: a monotonic_ns() count (telear/core/clock.hpp) as a steady_clock time point,
// for a condition variable's wait_until (the lease manager, the robot service).

#include <chrono>
#include <cstdint>

namespace telear::net {

inline std::chrono::steady_clock::time_point steady_time(std::int64_t ns) {
  // monotonic_ns() is steady_clock's count (core/clock.cpp).
  return std::chrono::steady_clock::time_point(std::chrono::nanoseconds(ns));
}

}  // namespace telear::net
