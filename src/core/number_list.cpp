#include "telear/core/number_list.hpp"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace telear::core {
namespace {

enum class NumberText { kNumber, kNotANumber, kNotFinite };

// The one strict reading of a number: strtod over the whole of `text` (no leading blank, no
// trailing junk, no overflow), finite.
NumberText read_number(const std::string& text, double& value) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text.front())) != 0) {
    return NumberText::kNotANumber;
  }
  char* end = nullptr;
  errno = 0;
  value = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0' || errno == ERANGE) return NumberText::kNotANumber;
  if (!std::isfinite(value)) return NumberText::kNotFinite;
  return NumberText::kNumber;
}

}  // namespace

Result<double> parse_number(const std::string& text, const std::string& what) {
  double value = 0.0;
  switch (read_number(text, value)) {
    case NumberText::kNumber:
      return value;
    case NumberText::kNotFinite:
      return Error{what + ": '" + text + "' is not a finite number"};
    case NumberText::kNotANumber:
      break;
  }
  return Error{what + ": '" + text + "' is not a number"};
}

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
    double value = 0.0;
    const NumberText read = read_number(item, value);
    if (read != NumberText::kNumber) {
      return Error{option + ": item " + std::to_string(index) + " ('" + item + "') is not a " +
                   (read == NumberText::kNotFinite ? "finite number" : "number")};
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
