#include "telear/net/latest_slot.hpp"

#include <gtest/gtest.h>

#include <thread>

namespace telear::net {
namespace {

using namespace std::chrono_literals;

TEST(LatestSlot, EmptySlotHasNothing) {
  LatestSlot<int> slot;
  EXPECT_FALSE(slot.try_take(0));
  EXPECT_FALSE(slot.wait_take(0, 1ms));
  EXPECT_EQ(slot.count(), 0u);
}

TEST(LatestSlot, KeepsOnlyTheNewestAndCountsWhatWasSkipped) {
  LatestSlot<int> slot;
  slot.put(10);
  slot.put(20);
  slot.put(30);
  auto first = slot.try_take(0);
  ASSERT_TRUE(first);
  EXPECT_EQ(*first->item, 30);
  EXPECT_EQ(first->number, 3u);
  EXPECT_EQ(first->skipped, 0u);   // a first take skips nothing by definition
  EXPECT_FALSE(slot.try_take(3));  // nothing newer than what was taken

  slot.put(40);
  slot.put(50);
  auto second = slot.try_take(3);
  ASSERT_TRUE(second);
  EXPECT_EQ(*second->item, 50);
  EXPECT_EQ(second->skipped, 1u);  // 40 was never seen
}

TEST(LatestSlot, ConsumersSkipIndependently) {
  LatestSlot<int> slot;
  slot.put(1);
  auto fast = slot.try_take(0);
  ASSERT_TRUE(fast);
  slot.put(2);
  slot.put(3);
  auto fast2 = slot.try_take(fast->number);
  auto slow = slot.try_take(0);
  ASSERT_TRUE(fast2 && slow);
  EXPECT_EQ(*fast2->item, 3);
  EXPECT_EQ(fast2->skipped, 1u);
  EXPECT_EQ(*slow->item, 3);  // the item stays for every consumer
}

TEST(LatestSlot, WaitTakeWakesOnPut) {
  LatestSlot<int> slot;
  std::thread producer([&] {
    std::this_thread::sleep_for(20ms);
    slot.put(7);
  });
  auto taken = slot.wait_take(0, 10s);
  producer.join();
  ASSERT_TRUE(taken);
  EXPECT_EQ(*taken->item, 7);
}

TEST(LatestSlot, CloseWakesWaitersForGood) {
  LatestSlot<int> slot;
  std::optional<LatestSlot<int>::Taken> result{LatestSlot<int>::Taken{}};
  std::thread consumer([&] { result = slot.wait_take(0, 10s); });
  std::this_thread::sleep_for(20ms);
  slot.close();
  consumer.join();
  EXPECT_FALSE(result);
  EXPECT_TRUE(slot.closed());
  slot.put(1);
  EXPECT_FALSE(slot.wait_take(0, 10s));  // returns at once once closed
}

}  // namespace
}  // namespace telear::net
