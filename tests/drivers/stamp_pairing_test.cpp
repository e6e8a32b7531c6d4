// The approximate-time pairing of the ROS 1 camera source (drivers/ros1/stamp_pairing.hpp) on
// stamp sequences chosen to reach each of its rules.
#include "drivers/ros1/stamp_pairing.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace telear::drivers::ros1 {
namespace {

constexpr std::int64_t kMs = 1000000;

using Pairing = StampPairing<int>;

// Adds (right?, stamp in ms) in order; returns the pairs as (left stamp, right stamp) in ms.
std::vector<std::pair<std::int64_t, std::int64_t>> feed(
    Pairing& pairing, const std::vector<std::pair<bool, std::int64_t>>& messages) {
  std::vector<std::pair<std::int64_t, std::int64_t>> made;
  for (const auto& [right, stamp_ms] : messages) {
    for (const auto& pair : pairing.add(right, stamp_ms * kMs, 0)) {
      made.emplace_back(pair.left_stamp_ns / kMs, pair.right_stamp_ns / kMs);
    }
  }
  return made;
}

TEST(StampPairing, EqualStampsPairAtOnce) {
  Pairing pairing(20 * kMs);
  EXPECT_TRUE(feed(pairing, {{false, 100}}).empty());
  EXPECT_EQ(feed(pairing, {{true, 100}}),
            (std::vector<std::pair<std::int64_t, std::int64_t>>{{100, 100}}));
}

TEST(StampPairing, FreeRunningCamerasPairWithoutWaitingOnceTheirPeriodIsKnown) {
  // Left at 0, 50, 100 ...; right 20 ms later. The first pair waits for the second left (the
  // period is not known yet); from then on each right completes its pair on arrival.
  Pairing pairing(25 * kMs);
  EXPECT_TRUE(feed(pairing, {{false, 0}, {true, 20}}).empty());
  EXPECT_EQ(feed(pairing, {{false, 50}}).size(), 1u);
  for (std::int64_t k = 1; k < 10; ++k) {
    const auto made = feed(pairing, {{true, 50 * k + 20}});
    ASSERT_EQ(made.size(), 1u) << k;
    EXPECT_EQ(made[0], std::make_pair(50 * k, 50 * k + 20));
    EXPECT_TRUE(feed(pairing, {{false, 50 * (k + 1)}}).empty());
  }
  EXPECT_EQ(pairing.dropped(false) + pairing.dropped(true), 0u);
}

TEST(StampPairing, ANearerLaterMessageTakesThePartner) {
  Pairing pairing(50 * kMs);
  EXPECT_TRUE(feed(pairing, {{false, 0}, {true, 40}}).empty());
  // The left at 45 is nearer the right at 40 than the left at 0 was: 0 is dropped. Whether a
  // right nearer 45 follows is known only when the next right comes (its period is unknown).
  EXPECT_TRUE(feed(pairing, {{false, 45}}).empty());
  EXPECT_EQ(pairing.dropped(false), 1u);
  EXPECT_EQ(feed(pairing, {{true, 90}}),
            (std::vector<std::pair<std::int64_t, std::int64_t>>{{45, 40}}));
  EXPECT_EQ(pairing.dropped(true), 0u);
}

TEST(StampPairing, MessagesFurtherApartThanTheToleranceNeverPair) {
  Pairing pairing(20 * kMs);
  EXPECT_TRUE(feed(pairing, {{false, 0}, {true, 50}, {false, 100}, {true, 150}}).empty());
  EXPECT_EQ(pairing.dropped(false), 2u);
  EXPECT_EQ(pairing.dropped(true), 1u);  // the right at 150 still waits for a left
}

TEST(StampPairing, ARepeatedStampIsDroppedAndAnOlderOneRestarts) {
  Pairing pairing(20 * kMs);
  EXPECT_EQ(feed(pairing, {{false, 1000}, {true, 1000}}).size(), 1u);
  EXPECT_TRUE(feed(pairing, {{false, 1000}}).empty());
  EXPECT_EQ(pairing.dropped(false), 1u);
  // The stamps went back (a bag played again): both streams start afresh.
  EXPECT_TRUE(feed(pairing, {{true, 2000}, {false, 500}}).empty());
  EXPECT_EQ(pairing.restarts(), 1u);
  EXPECT_EQ(pairing.dropped(true), 1u);
  EXPECT_EQ(feed(pairing, {{true, 500}}),
            (std::vector<std::pair<std::int64_t, std::int64_t>>{{500, 500}}));
}

TEST(StampPairing, AStreamWithoutPartnerKeepsAFewMessages) {
  Pairing pairing(20 * kMs, 4);
  for (std::int64_t k = 0; k < 10; ++k) EXPECT_TRUE(feed(pairing, {{false, 10 * k}}).empty());
  EXPECT_EQ(pairing.dropped(false), 6u);
  // The newest waiting left pairs with a right beside it; the older ones are dropped.
  EXPECT_EQ(feed(pairing, {{true, 90}}),
            (std::vector<std::pair<std::int64_t, std::int64_t>>{{90, 90}}));
  EXPECT_EQ(pairing.dropped(false), 9u);
}

}  // namespace
}  // namespace telear::drivers::ros1
