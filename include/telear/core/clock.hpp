#pragma once
// The clock every telear network timestamp is taken on: CLOCK_MONOTONIC in nanoseconds
// (std::chrono::steady_clock on Linux). It is the same clock in every process of one machine,
// so stamps from the servers and a client on loopback compare directly; across machines they
// differ by an offset that ClockOffsetEstimator (telear/net/clock_offset.hpp) estimates from Ping.

#include <chrono>
#include <cstdint>

namespace telear::core {

// Nanoseconds on the monotonic clock.
std::int64_t monotonic_ns();

inline double ns_to_s(std::int64_t ns) {
  return static_cast<double>(ns) * 1e-9;
}
inline std::int64_t s_to_ns(double s) {
  return static_cast<std::int64_t>(s * 1e9);
}

// Seconds elapsed on the steady clock since `start`: the workflows' timeouts and durations.
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace telear::core
