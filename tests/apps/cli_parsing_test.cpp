#include "apps/cli_parsing.hpp"

#include <gtest/gtest.h>

#include "telear/core/number_list.hpp"

namespace telear::cli {
namespace {

// The one list parser every option uses (moved from apps to core/number_list.hpp).
using core::parse_number_list;

TEST(ParseNumberList, ParsesCommaSeparatedNumbers) {
  auto v = parse_number_list(" 1, -2.5,3e-1", "--q");
  ASSERT_TRUE(v) << v.error().message;
  EXPECT_EQ(*v, (std::vector<double>{1.0, -2.5, 0.3}));
}

TEST(ParseNumberList, RejectsWhatIsNotAFiniteNumberList) {
  EXPECT_EQ(parse_number_list("1,,2", "--q").error().message, "--q: item 2 is empty in '1,,2'");
  EXPECT_EQ(parse_number_list("1,2,", "--q").error().message, "--q: item 3 is empty in '1,2,'");
  EXPECT_EQ(parse_number_list("1,2x", "--q").error().message, "--q: item 2 ('2x') is not a number");
  EXPECT_EQ(parse_number_list("inf", "--T").error().message,
            "--T: item 1 ('inf') is not a finite number");
  EXPECT_EQ(parse_number_list("1e999", "--T").error().message,
            "--T: item 1 ('1e999') is not a number");
  EXPECT_EQ(parse_number_list("1,2", "--q", 3).error().message, "--q: expected 3 numbers, got 2");
}

TEST(ImageSizeCheck, AcceptsSizesWithinTheBounds) {
  const auto check = image_size_check({64, 48}, {1920, 1080});
  std::string text = "640x480";
  EXPECT_EQ(check(text), "");
  text = "64x48";
  EXPECT_EQ(check(text), "");
  text = "1920x1080";
  EXPECT_EQ(check(text), "");
}

TEST(ImageSizeCheck, SaysWhyASizeIsRefused) {
  const auto check = image_size_check({64, 48}, {1920, 1080});
  std::string text = "20x10";
  EXPECT_EQ(check(text), "'20x10' is outside 64x48 .. 1920x1080");
  text = "1921x1080";
  EXPECT_EQ(check(text), "'1921x1080' is outside 64x48 .. 1920x1080");
  text = "640*480";
  EXPECT_EQ(check(text), "'640*480' is not WIDTHxHEIGHT (e.g. 640x480)");
  text = "";
  EXPECT_EQ(check(text), "'' is not WIDTHxHEIGHT (e.g. 640x480)");
}

TEST(ImageSizeCheck, ChecksEveryItemOfAList) {
  const auto check = image_size_check({16, 16}, {8192, 8192}, true);
  std::string text = "64x48,1280x720";
  EXPECT_EQ(check(text), "");
  text = "640x480,big";
  EXPECT_EQ(check(text), "'big' is not WIDTHxHEIGHT (e.g. 640x480)");
  text = "640x480,";
  EXPECT_EQ(check(text), "'' is not WIDTHxHEIGHT (e.g. 640x480)");
  text = "640x480,9000x480";
  EXPECT_EQ(check(text), "'9000x480' is outside 16x16 .. 8192x8192");
  text = "";
  EXPECT_EQ(check(text), "no size given; expected WIDTHxHEIGHT[,WIDTHxHEIGHT...]");
}

}  // namespace
}  // namespace telear::cli
