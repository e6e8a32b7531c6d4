#include "telear/core/number_list.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace telear::core {

Result<std::vector<double>> parse_number_list(const std::string& text, const std::string& option,
                                              int expected_count) {
  std::vector<double> values;
  std::stringstream stream(text);
  std::string item;
  int index = 0;
  while (std::getline(stream, item, ',')) {
    ++index;
    const size_t first = item.find_first_not_of(" \t");
    const size_t last = item.find_last_not_of(" \t");
    if (first == std::string::npos) {
      return Error{option + ": item " + std::to_string(index) + " is empty in '" + text + "'"};
    }
    item = item.substr(first, last - first + 1);
    char* end = nullptr;
    errno = 0;
    const double value = std::strtod(item.c_str(), &end);
    if (end == item.c_str() || *end != '\0' || errno == ERANGE) {
      return Error{option + ": item " + std::to_string(index) + " ('" + item +
                   "') is not a number"};
    }
    if (!std::isfinite(value)) {
      return Error{option + ": item " + std::to_string(index) + " ('" + item +
                   "') is not a finite number"};
    }
    values.push_back(value);
  }
  if (!text.empty() && text.back() == ',') {
    return Error{option + ": item " + std::to_string(index + 1) + " is empty in '" + text + "'"};
  }
  if (expected_count >= 0 && static_cast<int>(values.size()) != expected_count) {
    return Error{option + ": expected " + std::to_string(expected_count) + " numbers, got " +
                 std::to_string(values.size())};
  }
  return values;
}

Eigen::VectorXd to_vector(const std::vector<double>& values) {
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

}  // namespace telear::core
