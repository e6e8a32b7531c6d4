#include "telear/core/number_format.hpp"

#include <cstdio>

namespace telear::core {

std::string format_number(double value, const char* format) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

std::string format_fixed(double value, int digits, std::string_view unit) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", digits, value);
  std::string text = buffer;
  if (!unit.empty()) text.append(" ").append(unit);
  return text;
}

}  // namespace telear::core
