#pragma once
// Parsing of untrusted CLI values (comma-separated numbers, image sizes) with messages that
// name the option and the offending item. No CLI11 here (it is slow to compile): the CLI11
// validator in apps/cli_app.hpp wraps image_size_check.

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "telear/core/image_size.hpp"
#include "telear/core/result.hpp"

namespace telear::cli {

// "0.1,2,-3" -> {0.1, 2, -3}. Rejects empty items, trailing junk and non-finite values.
// `expected_count` < 0 accepts any count.
Result<std::vector<double>> parse_number_list(const std::string& text, const std::string& option,
                                              int expected_count = -1);

Eigen::VectorXd to_vector(const std::vector<double>& values);

// The body of the one WIDTHxHEIGHT validator (core::parse_image_size): returns "" when `text`
// is a size within [min, max], else the reason ("'20x10' is outside 64x48 .. 1920x1080").
// With `list`, `text` is comma-separated sizes ("640x480,1280x720"), each checked.
std::function<std::string(std::string&)> image_size_check(core::ImageSize min, core::ImageSize max,
                                                          bool list = false);

}  // namespace telear::cli
