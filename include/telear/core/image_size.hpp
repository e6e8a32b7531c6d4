#pragma once
// Image and window sizes written as "WIDTHxHEIGHT" (pixels, e.g. "640x480"): the one parser
// every option, file and message uses, so the accepted form, the bounds and the message read
// the same wherever a size is given. Untrusted text: the answer is a Result with the reason.

#include <string>
#include <string_view>

#include "telear/core/result.hpp"

namespace telear::core {

struct ImageSize {
  int width = 0;   // pixels
  int height = 0;  // pixels
  friend bool operator==(const ImageSize&, const ImageSize&) = default;
};

// "640x480": the text form, as parse_image_size reads it.
std::string to_string(const ImageSize& size);

// Reads "WIDTHxHEIGHT" (two decimal integers around one lower-case 'x', nothing else) and
// checks min.width <= width <= max.width, min.height <= height <= max.height. Messages:
//   "'640y480' is not WIDTHxHEIGHT (e.g. 640x480)"
//   "'20x10' is outside 64x48 .. 1920x1080"
// The caller prefixes the option or field name ("--resolution: ...").
Result<ImageSize> parse_image_size(std::string_view text, ImageSize min, ImageSize max);

}  // namespace telear::core
