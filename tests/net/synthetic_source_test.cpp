#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "telear/vision/synthetic_source.hpp"
#include "test_util/test_util.hpp"

namespace telear::net {
namespace {

using ::testing::HasSubstr;

TEST(SyntheticSource, MakesPairsOfTheAskedSizeNumberedFromOne) {
  vision::SyntheticSourceOptions options;
  options.width = 64;
  options.height = 48;
  options.fps = 1000;
  auto source = vision::SyntheticSource::create(options);
  ASSERT_TRUE(source) << source.error().message;
  for (std::uint64_t k = 1; k <= 3; ++k) {
    auto pair = (*source)->capture();
    ASSERT_TRUE(pair);
    EXPECT_EQ(pair->frame_number, k);
    EXPECT_EQ(pair->left.width, 64);
    EXPECT_EQ(pair->right.height, 48);
    EXPECT_GT(pair->capture_ns_left, 0);
    EXPECT_GE(pair->capture_ns_right, pair->capture_ns_left);
  }
}

TEST(SyntheticSource, RejectsBadOptions) {
  vision::SyntheticSourceOptions options;
  options.width = 8;
  auto source = vision::SyntheticSource::create(options);
  ASSERT_FALSE(source);
  EXPECT_THAT(source.error().message, HasSubstr("outside 16x16 .. 8192x8192"));
}

}  // namespace
}  // namespace telear::net
