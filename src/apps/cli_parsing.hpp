#pragma once
// Parsing of untrusted CLI values (comma-separated numbers) with messages that name the
// option and the offending item.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "telear/core/result.hpp"

namespace telear::cli {

// "0.1,2,-3" -> {0.1, 2, -3}. Rejects empty items, trailing junk and non-finite values.
// `expected_count` < 0 accepts any count.
Result<std::vector<double>> parse_number_list(const std::string& text, const std::string& option,
                                              int expected_count = -1);

Eigen::VectorXd to_vector(const std::vector<double>& values);

}  // namespace telear::cli
