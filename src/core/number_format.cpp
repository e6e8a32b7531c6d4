#include "telear/core/number_format.hpp"

#include <cstdio>

namespace telear::core {

std::string format_number(double value, const char* format) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

}  // namespace telear::core
