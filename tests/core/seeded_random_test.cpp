// core/seeded_random.hpp: splitmix64, the same numbers on every platform (the reference
// sequence of Steele, Lea and Flood's generator), so seeded IK restarts and sensor noise repeat.

#include "telear/core/seeded_random.hpp"

#include <gtest/gtest.h>

#include <cstdint>

namespace telear::core {
namespace {

TEST(SeededRandom, FollowsTheSplitmix64ReferenceSequence) {
  std::uint64_t state = 0;
  EXPECT_EQ(next_random(state), 0xe220a8397b1dcdafULL);
  EXPECT_EQ(next_random(state), 0x6e789e6aa1b965f4ULL);
  EXPECT_EQ(next_random(state), 0x06c45d188009454fULL);
}

TEST(SeededRandom, Uniform01TakesTheTop53Bits) {
  std::uint64_t state = 0;
  EXPECT_DOUBLE_EQ(uniform01(state), static_cast<double>(0xe220a8397b1dcdafULL >> 11) * 0x1.0p-53);
  for (int i = 0; i < 1000; ++i) {
    const double u = uniform01(state);
    EXPECT_GE(u, 0.0);
    EXPECT_LT(u, 1.0);
  }
}

TEST(SeededRandom, MixSeedIsTheFirstOutputOfAGeneratorSeededWithIt) {
  std::uint64_t state = 42;
  EXPECT_EQ(mix_seed(42), next_random(state));
  EXPECT_EQ(mix_seed(42), 0xbdd732262feb6e95ULL);
  EXPECT_NE(mix_seed(1), mix_seed(2));
  static_assert(mix_seed(0) == 0xe220a8397b1dcdafULL, "usable in constant expressions");
}

}  // namespace
}  // namespace telear::core
