#include "telear/core/ycbcr_image.hpp"

#include <algorithm>
#include <cmath>

namespace telear::core {
namespace {

std::uint8_t clamp_byte(double v) {
  return static_cast<std::uint8_t>(std::clamp(std::lround(v), 0L, 255L));
}

// The chroma sample coordinate (continuous, sample centres at integers) of a luma pixel's
// centre: chroma pixel k covers luma [k * f, (k + 1) * f), f the subsampling factor (an odd
// size's last chroma pixel covers the padding too).
double chroma_coordinate(int luma, int luma_size, int chroma_size) {
  return (luma + 0.5) / chroma_factor(luma_size, chroma_size) - 0.5;
}

}  // namespace

int chroma_factor(int luma_size, int chroma_size) {
  return chroma_size > 0 ? (luma_size + chroma_size - 1) / chroma_size : 1;
}

Image YCbCrImage::luma() const {
  Image grey(width, height, 1);
  grey.pixels = y;
  return grey;
}

Image to_rgb(const YCbCrImage& p) {
  const auto plane_size = [](int w, int h) { return static_cast<std::size_t>(w) * h; };
  if (p.width <= 0 || p.height <= 0 || p.chroma_width <= 0 || p.chroma_height <= 0 ||
      p.y.size() != plane_size(p.width, p.height) ||
      p.cb.size() != plane_size(p.chroma_width, p.chroma_height) || p.cr.size() != p.cb.size()) {
    return {};
  }
  Image rgb(p.width, p.height, 3);
  const auto sample = [&](const std::vector<std::uint8_t>& plane, double cx, double cy) {
    cx = std::clamp(cx, 0.0, static_cast<double>(p.chroma_width - 1));
    cy = std::clamp(cy, 0.0, static_cast<double>(p.chroma_height - 1));
    const int x0 = static_cast<int>(cx), y0 = static_cast<int>(cy);
    const int x1 = std::min(x0 + 1, p.chroma_width - 1), y1 = std::min(y0 + 1, p.chroma_height - 1);
    const double fx = cx - x0, fy = cy - y0;
    const auto at = [&](int x, int y) {
      return static_cast<double>(plane[static_cast<std::size_t>(y) * p.chroma_width + x]);
    };
    return (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x1, y0)) +
           fy * ((1 - fx) * at(x0, y1) + fx * at(x1, y1));
  };
  for (int row = 0; row < p.height; ++row) {
    const double cy = chroma_coordinate(row, p.height, p.chroma_height);
    for (int col = 0; col < p.width; ++col) {
      const double cx = chroma_coordinate(col, p.width, p.chroma_width);
      const double Y = p.y[static_cast<std::size_t>(row) * p.width + col];
      const double Cb = sample(p.cb, cx, cy) - 128.0, Cr = sample(p.cr, cx, cy) - 128.0;
      std::uint8_t* out = &rgb.at(col, row, 0);
      out[0] = clamp_byte(Y + 1.402 * Cr);
      out[1] = clamp_byte(Y - 0.344136 * Cb - 0.714136 * Cr);
      out[2] = clamp_byte(Y + 1.772 * Cb);
    }
  }
  return rgb;
}

}  // namespace telear::core
