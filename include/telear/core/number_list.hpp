#pragma once
// Numbers written on one line, as an operator types them ("0.1,2,-3" for --q, --pose, --T,
// --cameras): one parser, so every option refuses an empty item, trailing junk or a
// non-finite value with the same message naming the option and the item.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "telear/core/result.hpp"

namespace telear::core {

// "0.1,2,-3" -> {0.1, 2, -3}; blanks around an item are ignored. Errors: "--q: item 2 is
// empty in '1,,2'", "--q: item 2 ('2x') is not a number", "... is not a finite number",
// "--q: expected 6 numbers, got 3". `expected_count` < 0 accepts any count.
Result<std::vector<double>> parse_number_list(const std::string& text, const std::string& option,
                                              int expected_count = -1);

Eigen::VectorXd to_vector(const std::vector<double>& values);

}  // namespace telear::core
