#include "telear/core/ring_buffer.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>

namespace telear::core {
namespace {

TEST(RingBuffer, KeepsTheNewestCapacityOldestFirst) {
  RingBuffer<int> ring(3);
  EXPECT_TRUE(ring.empty());
  EXPECT_EQ(ring.capacity(), 3u);
  for (int v = 1; v <= 5; ++v) ring.push(v);
  EXPECT_TRUE(ring.full());
  ASSERT_EQ(ring.size(), 3u);
  EXPECT_EQ(ring[0], 3);
  EXPECT_EQ(ring[1], 4);
  EXPECT_EQ(ring[2], 5);
  EXPECT_EQ(ring.front(), 3);
  EXPECT_EQ(ring.back(), 5);
  ring.pop_front();
  EXPECT_EQ(ring.size(), 2u);
  EXPECT_EQ(ring.front(), 4);
  ring.push(6);
  ring.push(7);  // full again: 5 goes
  EXPECT_EQ(ring[0], 5);
  EXPECT_EQ(ring[2], 7);
  ring.clear();
  EXPECT_TRUE(ring.empty());
  ring.push(8);
  EXPECT_EQ(ring.front(), 8);
  EXPECT_EQ(ring.back(), 8);
}

// push() hands back the oldest slot once full: a vector of the same size is assigned in place,
// with no new allocation (the live series at a servo's rate).
TEST(RingBuffer, ReusesTheOldestSlotsStorage) {
  RingBuffer<Eigen::VectorXd> ring(2);
  ring.push() = Eigen::VectorXd::Constant(6, 1.0);
  ring.push() = Eigen::VectorXd::Constant(6, 2.0);
  const double* storage = ring[0].data();
  Eigen::VectorXd& slot = ring.push();
  EXPECT_EQ(slot.data(), storage);  // the oldest (1.0) vector's slot
  slot = Eigen::VectorXd::Constant(6, 3.0);
  EXPECT_EQ(ring.back().data(), storage);
  EXPECT_EQ(ring.front()[0], 2.0);
  EXPECT_EQ(ring.back()[0], 3.0);
}

}  // namespace
}  // namespace telear::core
