#include "apps/cli_parsing.hpp"

#include <gtest/gtest.h>

namespace telear::cli {
namespace {

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

}  // namespace
}  // namespace telear::cli
