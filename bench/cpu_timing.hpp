#pragma once
// CPU-clock timing for the kinematics benchmarks (`telear bench kin`): thread CPU time, so
// that time the scheduler gives to other processes is not counted, and the best of several
// batches, the least disturbed by them. Figures are ns per call.

#include <time.h>

#include <algorithm>
#include <limits>

namespace telear::bench {

// Thread CPU time: time the scheduler gives to other processes is not counted.
inline double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Keeps the compiler from discarding a result that is never read.
template <typename T>
inline void keep(const T& value) {
  asm volatile("" : : "m"(value) : "memory");
}

// CPU nanoseconds per call of call(i), i = 0, 1, ...: the best of `batches` batches of about
// `batch_seconds` each (the minimum is the least disturbed by other processes).
template <typename Call>
double best_ns_per_call(Call&& call, double batch_seconds = 0.02, int batches = 15) {
  long n = 16;
  for (;;) {
    const double t0 = cpu_seconds();
    for (long i = 0; i < n; ++i) call(i);
    const double dt = cpu_seconds() - t0;
    if (dt >= batch_seconds / 4 || n >= (1L << 26)) {
      n = std::max(n,
                   static_cast<long>(static_cast<double>(n) * batch_seconds / std::max(dt, 1e-9)));
      break;
    }
    n *= 4;
  }
  double best = std::numeric_limits<double>::infinity();
  for (int b = 0; b < batches; ++b) {
    const double t0 = cpu_seconds();
    for (long i = 0; i < n; ++i) call(i);
    best = std::min(best, (cpu_seconds() - t0) / static_cast<double>(n));
  }
  return best * 1e9;
}

}  // namespace telear::bench
