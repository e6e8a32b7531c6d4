#pragma once
// Internal to vision: small text helpers that several of its sources share (reports and
// messages, case-insensitive names), defined once.

#include <cctype>
#include <string>

#include "telear/core/number_format.hpp"

namespace telear::vision {

// `decimals` digits, fixed-point, no unit: fixed(0.12345, 3) == "0.123".
inline std::string fixed(double value, int decimals) {
  return core::format_fixed(value, decimals);
}

// ASCII upper case, for names compared without case (dictionaries, target specs).
inline std::string upper(std::string text) {
  for (char& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return text;
}

}  // namespace telear::vision
