#pragma once
// A video frame behind the scene: one RGBA8 texture, re-filled every frame (no
// re-allocation), put over the whole current viewport with depth untouched, so whatever is
// drawn next lands on top of it.
//
// Frames are 8-bit, 3 channels, RGB or BGR (OpenCV's order), top row first, tightly packed.
// upload() converts them on the CPU, in one pass, to RGBA with the rows in GL's bottom-up
// order (texel row 0 = the image's bottom row, so v = 1 is the image's top, the same upright
// convention as the arm's projection, view_math.hpp); the texture upload is then a plain
// copy. draw() copies the texture to the viewport with glBlitFramebuffer (an unscaled blit is
// a memory copy on llvmpipe, ~10x cheaper than a textured quad), or draws a textured quad
// where a blit is not allowed (a multisampled draw framebuffer). The frame is shown as is;
// lens-distortion handling (undistorted / raw modes) is the overlay's business: sample
// texture() with v = 1 - (row + 0.5) / height.
//
// upload_planes() takes a decoded JPEG's Y'CbCr planes instead (core/ycbcr_image.hpp): they
// go up as they are (three one-byte textures, no CPU pass over the pixels) and one draw
// converts them into the same RGBA texture (shaders.hpp, "ycbcr"), so everything after it is
// the same. On a GPU the conversion is free; on llvmpipe it is the CPU's again, but vectorised.

#include <cstdint>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/core/ycbcr_image.hpp"
#include "telear/render/gl_objects.hpp"

namespace telear::render {

enum class ChannelOrder { kRgb, kBgr };

class VideoBackground {
 public:
  VideoBackground() = default;
  // Allocates the texture for frames of this size. Needs a current context.
  static Result<VideoBackground> create(int width, int height);

  int width() const { return texture_.width(); }
  int height() const { return texture_.height(); }
  // Uploads one frame of width() x height() x 3 bytes.
  void upload(const std::uint8_t* pixels, ChannelOrder order = ChannelOrder::kBgr);
  // Uploads one frame's planes (luma width() x height(); chroma any size, e.g. 4:2:0's half).
  // Leaves the draw framebuffer, viewport and program bindings as it found them.
  void upload_planes(const core::YCbCrImage& planes);
  // Puts the last uploaded frame over the current viewport of the bound draw framebuffer
  // (scaled if the sizes differ). Leaves the read framebuffer binding as it found it.
  void draw() const;
  const Texture& texture() const { return texture_; }

 private:
  Texture texture_;
  Framebuffer framebuffer_;  // texture_ as a colour attachment: the blit's source
  VertexArray vao_;          // empty: the quad comes from gl_VertexID
  Program program_;
  std::vector<std::uint8_t> staging_;  // RGBA, bottom-up
  Program ycbcr_program_;              // linked at the first upload_planes()
  Texture luma_, cb_, cr_;             // the planes, top row first
};

}  // namespace telear::render
