// Nearest-rank percentiles (telear/net/latency_summary.hpp): always a measured value.
#include "telear/net/latency_summary.hpp"

#include <gtest/gtest.h>

namespace telear::net {
namespace {

TEST(LatencySummary, NearestRankPercentilesOfUnsortedSamples) {
  std::vector<double> v;
  for (int i = 100; i >= 1; --i) v.push_back(i * 1e-3);  // 1..100 ms, reversed
  EXPECT_DOUBLE_EQ(percentile(v, 50), 50e-3);
  EXPECT_DOUBLE_EQ(percentile(v, 99), 99e-3);
  EXPECT_DOUBLE_EQ(percentile(v, 100), 100e-3);
  EXPECT_DOUBLE_EQ(percentile({7.0, 3.0, 5.0}, 50), 5.0);
  const LatencySummary s = summarize_latency(v);
  EXPECT_EQ(s.samples, 100);
  EXPECT_DOUBLE_EQ(s.p50_s, 50e-3);
  EXPECT_DOUBLE_EQ(s.p99_s, 99e-3);
}

TEST(LatencySummary, NoSamplesGiveZeros) {
  const LatencySummary s = summarize_latency({});
  EXPECT_EQ(s.samples, 0);
  EXPECT_EQ(s.p50_s, 0.0);
  EXPECT_EQ(s.p99_s, 0.0);
}

}  // namespace
}  // namespace telear::net
