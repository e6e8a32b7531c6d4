#include "telear/render/offscreen_target.hpp"

#include "telear/core/image_size.hpp"
#include "telear/render/framebuffer_readback.hpp"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cstring>

namespace telear::render {

static_assert(std::endian::native == std::endian::little,
              "the pixel packing below assumes a little-endian CPU");

namespace {

Status check_complete(const core::ImageSize& size, const char* which) {
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status == GL_FRAMEBUFFER_COMPLETE) return Status::Ok();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return Error{"offscreen target " + core::to_string(size) + ": " + which +
               " framebuffer incomplete (status " + std::to_string(status) + ")"};
}

}  // namespace

Result<OffscreenTarget> OffscreenTarget::create(int width, int height, int samples) {
  const core::ImageSize size{width, height};
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
  if (width <= 0 || height <= 0 || width > max_size || height > max_size) {
    return Error{"offscreen target " + core::to_string(size) + ": size must be in [1, " +
                 std::to_string(max_size) + "]"};
  }
  GLint max_samples = 1;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  if (samples < 1 || samples > std::max(1, max_samples)) {
    return Error{"offscreen target " + core::to_string(size) + ": " + std::to_string(samples) +
                 " samples per pixel, this OpenGL driver allows 1 to " +
                 std::to_string(std::max(1, max_samples))};
  }
  OffscreenTarget t;
  t.width_ = width;
  t.height_ = height;
  t.samples_ = samples;
  t.colour_ = Texture::create_2d(width, height, GL_RGBA8);
  t.depth_ = samples > 1
                 ? Renderbuffer::create_multisample(width, height, samples, GL_DEPTH24_STENCIL8)
                 : Renderbuffer::create(width, height, GL_DEPTH24_STENCIL8);
  t.framebuffer_ = Framebuffer::create();
  t.framebuffer_.bind();
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, t.colour_.id(), 0);
  if (samples == 1) {
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                              t.depth_.id());
  }
  if (Status s = check_complete(size, "colour"); !s) return s.error();
  if (samples > 1) {
    t.multisample_colour_ = Renderbuffer::create_multisample(width, height, samples, GL_RGBA8);
    t.multisample_framebuffer_ = Framebuffer::create();
    t.multisample_framebuffer_.bind();
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                              t.multisample_colour_.id());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                              t.depth_.id());
    if (Status s = check_complete(size, "multisample"); !s) return s.error();
  }
  return t;
}

void OffscreenTarget::bind() const {
  draw_framebuffer().bind();
  glViewport(0, 0, width_, height_);
}

void OffscreenTarget::bind_viewport(int x, int y, int width, int height) const {
  draw_framebuffer().bind();
  glViewport(x, y, width, height);
}

void OffscreenTarget::resolve() const {
  if (samples_ == 1) return;
  multisample_framebuffer_.bind(GL_READ_FRAMEBUFFER);
  framebuffer_.bind(GL_DRAW_FRAMEBUFFER);
  glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  draw_framebuffer().bind();
}

void OffscreenTarget::clear(float r, float g, float b, float a) const {
  draw_framebuffer().bind();
  glViewport(0, 0, width_, height_);
  glDepthMask(GL_TRUE);
  glClearColor(r, g, b, a);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
}

void OffscreenTarget::clear_depth() const {
  draw_framebuffer().bind();
  glViewport(0, 0, width_, height_);
  glDepthMask(GL_TRUE);
  glClearDepth(1.0);
  glClear(GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
}

void OffscreenTarget::read_pixels(int channels, std::uint8_t* pixels) const {
  assert((channels == 3 || channels == 4) && "OffscreenTarget::read_pixels(): 3 or 4 channels");
  // RGBA is the driver's fast path (a copy on llvmpipe; RGB is ~4x slower); the row flip
  // into image order and the RGBA -> RGB packing are one CPU pass over the scratch copy.
  resolve();
  framebuffer_.bind(GL_READ_FRAMEBUFFER);
  read_bound_framebuffer(width_, height_, channels, pixels, scratch_);
}

void OffscreenTarget::read_region(int x, int y, int width, int height, int channels,
                                  std::uint8_t* pixels) const {
  assert((channels == 3 || channels == 4) && "OffscreenTarget::read_region(): 3 or 4 channels");
  assert(x >= 0 && y >= 0 && width > 0 && height > 0 && x + width <= width_ &&
         y + height <= height_ && "OffscreenTarget::read_region(): outside the target");
  resolve();
  framebuffer_.bind(GL_READ_FRAMEBUFFER);
  read_bound_framebuffer_region(x, height_ - y - height, width, height, channels, pixels, scratch_);
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
