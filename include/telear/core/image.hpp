#pragma once
// An 8-bit image in memory, the exchange format of render/ (no OpenCV at this level):
// width x height x channels bytes, row-major, TOP row first, tightly packed (no padding).
// channels: 1 (grey), 3 (RGB) or 4 (RGBA). Wrap it without a copy as
// cv::Mat(height, width, CV_8UC(channels), pixels.data()) -- note RGB, not BGR, order.

#include <cstdint>
#include <vector>

namespace telear::core {

struct Image {
  int width = 0;
  int height = 0;
  int channels = 0;
  std::vector<std::uint8_t> pixels;

  Image() = default;
  Image(int w, int h, int c)
      : width(w), height(h), channels(c), pixels(static_cast<std::size_t>(w) * h * c, 0) {}

  bool empty() const { return pixels.empty(); }
  std::size_t row_bytes() const { return static_cast<std::size_t>(width) * channels; }
  std::uint8_t* row(int y) { return pixels.data() + static_cast<std::size_t>(y) * row_bytes(); }
  const std::uint8_t* row(int y) const {
    return pixels.data() + static_cast<std::size_t>(y) * row_bytes();
  }
  std::uint8_t& at(int x, int y, int c) { return row(y)[x * channels + c]; }
  std::uint8_t at(int x, int y, int c) const { return row(y)[x * channels + c]; }
};

}  // namespace telear::core
