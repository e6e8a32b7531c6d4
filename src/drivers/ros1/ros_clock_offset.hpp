#pragma once
// Header stamps on the server clock. ROS 1 stamps are ROS time (the system clock, unless the
// graph runs on /use_sim_time); telear's servers stamp with CLOCK_MONOTONIC. A stamp becomes
//   capture_ns = stamp + (monotonic - ROS time),
// the offset read as a bracket: monotonic, ROS time, monotonic. A thread preempted between two
// reads (a loaded machine) would otherwise move every stamp it converts by the time it was
// away, and two eyes stamped 50 ms apart would land 48.9 ms apart (a CI run); so the offset of
// the narrowest bracket is kept, renewed after a second by a bracket that was not preempted
// (both clocks are slewed alike by NTP; a step of the system clock is picked up within the
// second). Replacing it by whatever the next reading gave once a second moved a pair that
// straddled the renewal by half a preempted bracket (0.48 ms in a CI run).
//
// Header-only and C++17: the C++17 units that see ROS include it. Thread-safe.

#include <ros/time.h>
#include <time.h>

#include <cstdint>
#include <limits>
#include <mutex>

namespace telear::drivers::ros1 {

inline std::int64_t monotonic_clock_ns() {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  return std::int64_t{now.tv_sec} * 1'000'000'000 + now.tv_nsec;
}

class RosClockOffset {
 public:
  struct Reading {
    std::int64_t monotonic_ns = 0;  // now, on the server clock
    std::int64_t ros_ns = 0;        // now, ROS time
    std::int64_t offset_ns = 0;     // the kept estimate of monotonic - ROS time
  };

  Reading read() {
    // Up to a few brackets until one was not preempted (the first reading of all has nothing
    // to fall back on: the first frames of a stream are converted with it).
    std::int64_t before = 0, ros = 0, after = 0, width = 0;
    for (int attempt = 0; attempt < 8; ++attempt) {
      before = monotonic_clock_ns();
      ros = static_cast<std::int64_t>(ros::Time::now().toNSec());
      after = monotonic_clock_ns();
      width = after - before;
      if (width <= kUnpreempted_ns) break;
    }
    const std::int64_t offset = before + width / 2 - ros;
    std::lock_guard lock(mutex_);
    // A narrower bracket always; after a second (to follow a step of the system clock) any
    // bracket that was not preempted; after ten, or at the first reading, whatever there is.
    const std::int64_t age = after - best_at_;
    if (width <= best_width_ || (age > kKeep_ns && width <= kUnpreempted_ns) ||
        age > 10 * kKeep_ns) {
      best_width_ = width;
      best_offset_ = offset;
      best_at_ = after;
    }
    return {after, ros + width / 2, best_offset_};
  }

  // The stamp (ROS ns) on the server clock, with `reading` from the receipt: at the receipt for
  // no stamp (0) or one ahead of this machine's ROS clock (unsynchronised machines).
  static std::int64_t capture_ns(std::int64_t stamp_ns, const Reading& reading) {
    if (stamp_ns <= 0 || stamp_ns > reading.ros_ns) return reading.monotonic_ns;
    return stamp_ns + reading.offset_ns;
  }

 private:
  static constexpr std::int64_t kKeep_ns = 1'000'000'000;
  // Three clock reads take well under a microsecond; a wider bracket had the thread preempted.
  static constexpr std::int64_t kUnpreempted_ns = 20'000;
  std::mutex mutex_;
  std::int64_t best_width_ = std::numeric_limits<std::int64_t>::max();
  std::int64_t best_offset_ = 0;
  std::int64_t best_at_ = 0;
};

}  // namespace telear::drivers::ros1
