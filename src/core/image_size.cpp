#include "telear/core/image_size.hpp"

#include <charconv>

namespace telear::core {
namespace {

// A positive decimal integer filling `text` entirely (no sign, no blanks), or -1.
int whole_number(std::string_view text) {
  int value = -1;
  if (text.empty() || text.front() < '0' || text.front() > '9') return -1;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc{} || end != text.data() + text.size()) return -1;
  return value;
}

}  // namespace

std::string to_string(const ImageSize& size) {
  return std::to_string(size.width) + "x" + std::to_string(size.height);
}

Result<ImageSize> parse_image_size(std::string_view text, ImageSize min, ImageSize max) {
  // Built by appending: GCC 12 warns (-Wrestrict, a known false positive) on "'" + s + "'".
  std::string quoted(1, '\'');
  quoted.append(text);
  quoted.push_back('\'');
  const auto x = text.find('x');
  const ImageSize size{x == std::string_view::npos ? -1 : whole_number(text.substr(0, x)),
                       x == std::string_view::npos ? -1 : whole_number(text.substr(x + 1))};
  if (size.width < 0 || size.height < 0) {
    return Error{quoted + " is not WIDTHxHEIGHT (e.g. 640x480)"};
  }
  if (size.width < min.width || size.height < min.height || size.width > max.width ||
      size.height > max.height) {
    return Error{quoted + " is outside " + to_string(min) + " .. " + to_string(max)};
  }
  return size;
}

}  // namespace telear::core
