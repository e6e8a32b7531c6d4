// to_string(ImageSize): the one "WIDTHxHEIGHT" every message and report prints, the form
// parse_image_size reads back.

#include <gtest/gtest.h>

#include <string>

#include "telear/core/image_size.hpp"

namespace telear::core {
namespace {

TEST(ImageSizeText, IsWidthByHeightInDecimal) {
  EXPECT_EQ(to_string(ImageSize{640, 480}), "640x480");
  EXPECT_EQ(to_string(ImageSize{1920, 1080}), "1920x1080");
  EXPECT_EQ(to_string(ImageSize{0, 0}), "0x0");
  EXPECT_EQ(to_string(ImageSize{-1, 5}), "-1x5");  // a refused size is printed as it came
  EXPECT_EQ("frame " + to_string(ImageSize{32, 24}) + " is empty", "frame 32x24 is empty");
}

TEST(ImageSizeText, IsReadBackByParseImageSize) {
  for (const ImageSize size : {ImageSize{16, 16}, ImageSize{640, 480}, ImageSize{8192, 4320}}) {
    const auto parsed = parse_image_size(to_string(size), {16, 16}, {8192, 8192});
    ASSERT_TRUE(parsed) << parsed.error().message;
    EXPECT_EQ(*parsed, size);
  }
}

}  // namespace
}  // namespace telear::core
