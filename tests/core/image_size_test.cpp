// parse_image_size: the one WIDTHxHEIGHT reader (bounds inclusive, garbage refused, message
// text).

#include "telear/core/image_size.hpp"

#include <gtest/gtest.h>

namespace telear::core {
namespace {

constexpr ImageSize kMin{64, 48};
constexpr ImageSize kMax{1920, 1080};

TEST(ParseImageSize, ReadsWidthByHeight) {
  auto size = parse_image_size("640x480", kMin, kMax);
  ASSERT_TRUE(size) << size.error().message;
  EXPECT_EQ(*size, (ImageSize{640, 480}));
  EXPECT_EQ(to_string(*size), "640x480");
}

TEST(ParseImageSize, BoundsAreInclusive) {
  EXPECT_TRUE(parse_image_size("64x48", kMin, kMax));
  EXPECT_TRUE(parse_image_size("1920x1080", kMin, kMax));
  EXPECT_EQ(parse_image_size("63x48", kMin, kMax).error().message,
            "'63x48' is outside 64x48 .. 1920x1080");
  EXPECT_EQ(parse_image_size("64x1081", kMin, kMax).error().message,
            "'64x1081' is outside 64x48 .. 1920x1080");
  EXPECT_EQ(parse_image_size("20x10", kMin, kMax).error().message,
            "'20x10' is outside 64x48 .. 1920x1080");
}

TEST(ParseImageSize, RefusesWhatIsNotWidthByHeight) {
  for (const char* text :
       {"", "x", "640", "640x", "x480", "640X480", "640y480", "640x480x2", " 640x480", "640x480 ",
        "-640x480", "+640x480", "640.5x480", "big", "99999999999x480"}) {
    const auto size = parse_image_size(text, kMin, kMax);
    ASSERT_FALSE(size) << text;
    std::string expected = "'";
    expected.append(text).append("' is not WIDTHxHEIGHT (e.g. 640x480)");
    EXPECT_EQ(size.error().message, expected);
  }
}

}  // namespace
}  // namespace telear::core
