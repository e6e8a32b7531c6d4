#pragma once
// Percentiles of measured latencies: the one definition the session's status, the demo's
// report and `telear bench stream` share. Nearest rank: the p-th percentile of n sorted
// samples is sample ceil(p n) (1-based), a value that was actually measured.

#include <vector>

namespace telear::net {

struct LatencySummary {
  double p50_s = 0.0, p99_s = 0.0;  // 0 when there are no samples
  int samples = 0;
};

// Nearest-rank percentile, p in (0, 100], of `values` (any unit); 0 when empty.
double percentile(std::vector<double> values, double p);

LatencySummary summarize_latency(const std::vector<double>& seconds);

}  // namespace telear::net
