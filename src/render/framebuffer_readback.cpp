#include "telear/render/framebuffer_readback.hpp"

#include <epoxy/gl.h>

#include <algorithm>

#include <cstring>

namespace telear::render {

void read_bound_framebuffer(int width, int height, int channels, std::uint8_t* pixels,
                            std::vector<std::uint8_t>& scratch) {
  read_bound_framebuffer_region(0, 0, width, height, channels, pixels, scratch);
}

void read_bound_framebuffer_region(int x, int y_bottom, int width, int height, int channels,
                                   std::uint8_t* pixels, std::vector<std::uint8_t>& scratch) {
  const std::size_t w = static_cast<std::size_t>(width);
  scratch.resize(w * static_cast<std::size_t>(height) * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(x, y_bottom, width, height, GL_RGBA, GL_UNSIGNED_BYTE, scratch.data());
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* s = scratch.data() + static_cast<std::size_t>(height - 1 - y) * w * 4;
    std::uint8_t* d = pixels + static_cast<std::size_t>(y) * w * static_cast<std::size_t>(channels);
    if (channels == 4) {
      std::copy(s, s + w * 4, d);
      continue;
    }
    // RGBA -> RGB, four pixels (two 64-bit words) into 12 bytes by shifts and masks: ~4x
    // faster than byte-wise copying (32-bit words are slower here: partial store forwarding).
    const std::size_t groups = w / 4;
    for (std::size_t g = 0; g < groups; ++g) {
      std::uint64_t in[2];
      std::memcpy(in, s + 16 * g, sizeof in);
      const std::uint64_t lo =
          (in[0] & 0xFFFFFFull) | ((in[0] >> 8) & 0xFFFFFF000000ull) | (in[1] << 48);
      const auto hi =
          static_cast<std::uint32_t>(((in[1] >> 16) & 0xFFull) | ((in[1] >> 24) & 0xFFFFFF00ull));
      std::memcpy(d + 12 * g, &lo, sizeof lo);
      std::memcpy(d + 12 * g + 8, &hi, sizeof hi);
    }
    for (std::size_t x = groups * 4; x < w; ++x) {
      d[3 * x + 0] = s[4 * x + 0];
      d[3 * x + 1] = s[4 * x + 1];
      d[3 * x + 2] = s[4 * x + 2];
    }
  }
}

core::Image read_bound_framebuffer_rgb(int width, int height) {
  core::Image image(width, height, 3);
  std::vector<std::uint8_t> scratch;
  read_bound_framebuffer(width, height, 3, image.pixels.data(), scratch);
  return image;
}

}  // namespace telear::render
