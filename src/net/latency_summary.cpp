#include "telear/net/latency_summary.hpp"

#include <algorithm>
#include <cmath>

namespace telear::net {

double percentile(std::vector<double> values, double p) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const auto rank = static_cast<std::size_t>(std::ceil(p / 100.0 * values.size()));
  return values[std::clamp<std::size_t>(rank, 1, values.size()) - 1];
}

LatencySummary summarize_latency(const std::vector<double>& seconds) {
  return {percentile(seconds, 50), percentile(seconds, 99), static_cast<int>(seconds.size())};
}

}  // namespace telear::net
