#pragma once
// Numbers written as text, as an operator types them: one number ("2.5" for a script's
// value, a console field) or a list on one line ("0.1,2,-3" for --q, --pose, --T, --cameras).
// One strict reading for both, so every field refuses an empty item, trailing junk ("2abc")
// or a non-finite value with the same message naming the field (and the item).

#include <Eigen/Core>
#include <string>
#include <vector>

#include "telear/core/result.hpp"

namespace telear::core {

// The whole of `text` as one finite number: "2.5" -> 2.5. No blanks around it. Errors:
// "angle: '2abc' is not a number", "angle: 'inf' is not a finite number" (`what` names the
// field).
Result<double> parse_number(const std::string& text, const std::string& what);

// "0.1,2,-3" -> {0.1, 2, -3}; blanks around an item are ignored. Errors: "--q: item 2 is
// empty in '1,,2'", "--q: item 2 ('2x') is not a number", "... is not a finite number",
// "--q: expected 6 numbers, got 3". `expected_count` < 0 accepts any count.
Result<std::vector<double>> parse_number_list(const std::string& text, const std::string& option,
                                              int expected_count = -1);

Eigen::VectorXd to_vector(const std::vector<double>& values);

}  // namespace telear::core
