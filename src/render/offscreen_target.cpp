#include "telear/render/offscreen_target.hpp"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cstring>

namespace telear::render {

static_assert(std::endian::native == std::endian::little,
              "the pixel packing below assumes a little-endian CPU");

Result<OffscreenTarget> OffscreenTarget::create(int width, int height) {
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
  if (width <= 0 || height <= 0 || width > max_size || height > max_size) {
    return Error{"offscreen target " + std::to_string(width) + "x" + std::to_string(height) +
                 ": size must be in [1, " + std::to_string(max_size) + "]"};
  }
  OffscreenTarget t;
  t.width_ = width;
  t.height_ = height;
  t.colour_ = Texture::create_2d(width, height, GL_RGBA8);
  t.depth_ = Renderbuffer::create(width, height, GL_DEPTH24_STENCIL8);
  t.framebuffer_ = Framebuffer::create();
  t.framebuffer_.bind();
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, t.colour_.id(), 0);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                            t.depth_.id());
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return Error{"offscreen target " + std::to_string(width) + "x" + std::to_string(height) +
                 ": framebuffer incomplete (status " + std::to_string(status) + ")"};
  }
  return t;
}

void OffscreenTarget::bind() const {
  framebuffer_.bind();
  glViewport(0, 0, width_, height_);
}

void OffscreenTarget::bind_viewport(int x, int y, int width, int height) const {
  framebuffer_.bind();
  glViewport(x, y, width, height);
}

void OffscreenTarget::clear(float r, float g, float b, float a) const {
  framebuffer_.bind();
  glViewport(0, 0, width_, height_);
  glDepthMask(GL_TRUE);
  glClearColor(r, g, b, a);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
}

void OffscreenTarget::clear_depth() const {
  framebuffer_.bind();
  glViewport(0, 0, width_, height_);
  glDepthMask(GL_TRUE);
  glClearDepth(1.0);
  glClear(GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
}

void OffscreenTarget::read_pixels(int channels, std::uint8_t* pixels) const {
  assert((channels == 3 || channels == 4) && "OffscreenTarget::read_pixels(): 3 or 4 channels");
  // RGBA is the driver's fast path (a copy on llvmpipe; RGB is ~4x slower); the row flip
  // into image order and the RGBA -> RGB packing are one CPU pass over the scratch copy.
  const std::size_t w = static_cast<std::size_t>(width_);
  scratch_.resize(w * static_cast<std::size_t>(height_) * 4);
  framebuffer_.bind(GL_READ_FRAMEBUFFER);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, scratch_.data());
  for (int y = 0; y < height_; ++y) {
    const std::uint8_t* s = scratch_.data() + static_cast<std::size_t>(height_ - 1 - y) * w * 4;
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

core::Image OffscreenTarget::read_rgb() const {
  core::Image image(width_, height_, 3);
  read_pixels(3, image.pixels.data());
  return image;
}

core::Image OffscreenTarget::read_rgba() const {
  core::Image image(width_, height_, 4);
  read_pixels(4, image.pixels.data());
  return image;
}

}  // namespace telear::render
