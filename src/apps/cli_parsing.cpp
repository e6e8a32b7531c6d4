#include "apps/cli_parsing.hpp"

#include <sstream>

namespace telear::cli {

std::function<std::string(std::string&)> image_size_check(core::ImageSize min, core::ImageSize max,
                                                          bool list) {
  return [min, max, list](std::string& text) -> std::string {
    if (!list) {
      const auto size = core::parse_image_size(text, min, max);
      return size ? "" : size.error().message;
    }
    if (text.empty()) return "no size given; expected WIDTHxHEIGHT[,WIDTHxHEIGHT...]";
    std::stringstream items(text + ",");  // so that a trailing ',' reads an empty item
    for (std::string item; std::getline(items, item, ',');) {
      const auto size = core::parse_image_size(item, min, max);
      if (!size) return size.error().message;
    }
    return "";
  };
}

}  // namespace telear::cli
