// parse_number and parse_number_list: the one strict reading of numbers typed as text. The whole
// text must be one finite number ("2abc" is refused, not read as 2), and the message names the
// field (and the item of a list).

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "telear/core/number_list.hpp"

namespace telear::core {
namespace {

TEST(ParseNumber, ReadsTheWholeTextAsOneFiniteNumber) {
  for (const auto& [text, value] : std::vector<std::pair<std::string, double>>{
           {"2", 2.0}, {"-0.25", -0.25}, {"1e-3", 1e-3}, {"+7", 7.0}, {".5", 0.5}}) {
    const auto number = parse_number(text, "angle");
    ASSERT_TRUE(number) << text << ": " << number.error().message;
    EXPECT_EQ(*number, value) << text;
  }
}

TEST(ParseNumber, RefusesTrailingJunkNamingTheField) {
  const auto number = parse_number("2abc", "joint 1");
  ASSERT_FALSE(number);
  EXPECT_EQ(number.error().message, "joint 1: '2abc' is not a number");
}

TEST(ParseNumber, RefusesEmptyBlankAndOverflowingText) {
  EXPECT_EQ(parse_number("", "wait").error().message, "wait: '' is not a number");
  EXPECT_EQ(parse_number(" 2", "wait").error().message, "wait: ' 2' is not a number");
  EXPECT_EQ(parse_number("2 ", "wait").error().message, "wait: '2 ' is not a number");
  EXPECT_EQ(parse_number("1e999", "wait").error().message, "wait: '1e999' is not a number");
  EXPECT_EQ(parse_number("x", "wait").error().message, "wait: 'x' is not a number");
}

TEST(ParseNumber, RefusesNonFiniteValues) {
  EXPECT_EQ(parse_number("inf", "length").error().message, "length: 'inf' is not a finite number");
  EXPECT_EQ(parse_number("-inf", "length").error().message,
            "length: '-inf' is not a finite number");
  EXPECT_EQ(parse_number("nan", "length").error().message, "length: 'nan' is not a finite number");
}

// The console's typed joint values go through parse_number_list: an item with trailing junk is
// refused with its position instead of being read as its leading digits.
TEST(ParseNumberList, RefusesAnItemWithTrailingJunk) {
  const auto values = parse_number_list("10,2abc,3", "joint values");
  ASSERT_FALSE(values);
  EXPECT_EQ(values.error().message, "joint values: item 2 ('2abc') is not a number");
  const auto good = parse_number_list("10, -20 ,3.5", "joint values");
  ASSERT_TRUE(good) << good.error().message;
  EXPECT_EQ(*good, (std::vector<double>{10.0, -20.0, 3.5}));
}

TEST(ParseNumberList, ReadsItemsAsParseNumberDoes) {
  EXPECT_EQ(parse_number_list("1,inf", "--q").error().message,
            "--q: item 2 ('inf') is not a finite number");
  EXPECT_EQ(parse_number_list("1,1e999", "--q").error().message,
            "--q: item 2 ('1e999') is not a number");
}

}  // namespace
}  // namespace telear::core
