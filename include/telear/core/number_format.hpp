#pragma once
// Numbers in messages and tables: printf formatting into a std::string, so texts read the
// same wherever they are made ("%g" by default: 0.01, 1e-09, 480), fixed-point numbers with a
// unit ("12.50 deg", "0.4521 m", "33 ms") and table rows of several values: the one formatter
// for all three (no local snprintf wrappers).

#include <string>
#include <string_view>

namespace telear::core {

std::string format_number(double value, const char* format = "%g");

// Several values in one printf format, for a table row or a message with a few numbers:
// format_values("%.3f px (alone %.3f)", rms, alone). Never truncated; the format is checked
// against the arguments at compile time.
std::string format_values(const char* format, ...) __attribute__((format(printf, 1, 2)));

// `digits` decimals, fixed-point (printf's "%.*f"), then " unit" when `unit` is not empty:
// format_fixed(12.5, 2, "deg") == "12.50 deg", format_fixed(0.0333, 0) == "0".
std::string format_fixed(double value, int digits, std::string_view unit = {});

}  // namespace telear::core
