#pragma once
// The CLI's WIDTHxHEIGHT check (lists of numbers: core/number_list.hpp; joint values:
// core/joint_values.hpp). No CLI11 here (it is slow to compile): the CLI11
// validator in apps/cli_app.hpp wraps image_size_check.

#include <functional>
#include <string>

#include "telear/core/image_size.hpp"
#include "telear/core/result.hpp"

namespace telear::cli {

// The body of the one WIDTHxHEIGHT validator (core::parse_image_size): returns "" when `text`
// is a size within [min, max], else the reason ("'20x10' is outside 64x48 .. 1920x1080").
// With `list`, `text` is comma-separated sizes ("640x480,1280x720"), each checked.
std::function<std::string(std::string&)> image_size_check(core::ImageSize min, core::ImageSize max,
                                                          bool list = false);

}  // namespace telear::cli
