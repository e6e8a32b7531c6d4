#pragma once
// Numbers in messages: printf formatting into a std::string, so error texts read the same
// wherever they are made ("%g" by default: 0.01, 1e-09, 480).

#include <string>

namespace telear::core {

std::string format_number(double value, const char* format = "%g");

}  // namespace telear::core
