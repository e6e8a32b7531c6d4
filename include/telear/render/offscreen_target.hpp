#pragma once
// Render-to-texture: a framebuffer object with an RGBA8 colour texture and a 24-bit depth
// (+ 8-bit stencil) renderbuffer, and read-back to memory in IMAGE order (top row first).
//
// Multisampled (samples > 1): drawing goes to multisample colour and depth renderbuffers, and
// resolve() averages each pixel's samples into the colour texture, so an edge pixel holds the
// part of its area each surface covers (what a camera's pixel integrates) instead of the one
// surface its centre hits (point sampling: edges on a staircase of whole pixels). read_pixels()
// resolves by itself; a caller sampling colour_texture() calls resolve() after drawing.
//
// The colour texture is GL's usual bottom-up layout (texel row 0 = the image's bottom row,
// see view_math.hpp); sample it with v = 1 at the image top when composing (stereo layouts,
// the console), or read it back with read_rgb() / read_rgba(), which flip the rows.

#include <epoxy/gl.h>

#include <cstdint>
#include <vector>

#include "telear/core/image.hpp"
#include "telear/core/result.hpp"
#include "telear/render/gl_objects.hpp"

namespace telear::render {

class OffscreenTarget {
 public:
  OffscreenTarget() = default;  // empty; no GL
  // Needs a current context. Errors: size not positive or above GL_MAX_RENDERBUFFER_SIZE,
  // or the framebuffer is incomplete. `samples` per pixel: 1 (no multisampling) up to
  // GL_MAX_SAMPLES; more is an error naming the driver's limit.
  static Result<OffscreenTarget> create(int width, int height, int samples = 1);

  int width() const { return width_; }
  int height() const { return height_; }
  int samples() const { return samples_; }
  // Binds the framebuffer for drawing and reading and sets the viewport to all of it.
  void bind() const;
  // Sets the viewport to the sub-rectangle (x, y from the bottom-left, GL's convention);
  // the stereo layouts draw each eye into one half.
  void bind_viewport(int x, int y, int width, int height) const;
  // Clears colour (the given RGBA) and depth of the whole target.
  void clear(float r = 0.f, float g = 0.f, float b = 0.f, float a = 1.f) const;
  // Clears depth (and stencil) only: for frames whose colour a video background replaces.
  void clear_depth() const;

  // The framebuffer drawing goes to (the multisample one when samples() > 1).
  GLuint framebuffer_id() const { return draw_framebuffer().id(); }
  // The colour as a texture; when multisampled, as of the last resolve().
  const Texture& colour_texture() const { return colour_; }
  // Multisampled: averages the samples into colour_texture(); otherwise nothing to do.
  void resolve() const;

  // Reads the whole target into `pixels` (width * height * channels bytes, channels 3 = RGB
  // or 4 = RGBA), top row first. Waits for rendering to finish (glReadPixels).
  void read_pixels(int channels, std::uint8_t* pixels) const;
  core::Image read_rgb() const;
  core::Image read_rgba() const;
  // Reads only the rectangle whose top-left pixel is (x, y) in image order (top row first),
  // as read_pixels() does the whole target; it must lie within the target (asserted).
  void read_region(int x, int y, int width, int height, int channels, std::uint8_t* pixels) const;

 private:
  const Framebuffer& draw_framebuffer() const {
    return samples_ > 1 ? multisample_framebuffer_ : framebuffer_;
  }

  Framebuffer framebuffer_;  // the colour texture (the resolved image when multisampled)
  Texture colour_;
  Renderbuffer depth_;
  Framebuffer multisample_framebuffer_;  // samples_ > 1 only
  Renderbuffer multisample_colour_;
  int samples_ = 1;
  mutable std::vector<std::uint8_t> scratch_;  // RGBA bottom-up read-back
  int width_ = 0;
  int height_ = 0;
};

}  // namespace telear::render
