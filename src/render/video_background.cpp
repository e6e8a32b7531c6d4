#include "telear/render/video_background.hpp"

#include <bit>
#include <cassert>
#include <cstring>

#include "telear/core/image_size.hpp"
#include "telear/render/shaders.hpp"

namespace telear::render {

static_assert(std::endian::native == std::endian::little,
              "the pixel packing below assumes a little-endian CPU");
namespace {

std::uint32_t swap_red_blue(std::uint32_t v) {
  return (v & 0xFF00FF00u) | ((v & 0xFFu) << 16) | ((v >> 16) & 0xFFu);
}

// One row, RGB (or BGR) -> RGBA with alpha 255. Four pixels at a time: three 32-bit words
// in (R0 G0 B0 R1 | G1 B1 R2 G2 | B2 R3 G3 B3, little-endian as on every CPU telear targets)
// become four words out by shifts and masks; ~2x faster than byte-wise copying.
template <bool kBgr>
void expand_row(const std::uint8_t* s, std::uint8_t* d, int width) {
  constexpr std::uint32_t kAlpha = 0xFF000000u;
  const int groups = width / 4;
  for (int g = 0; g < groups; ++g) {
    std::uint32_t in[3];
    std::memcpy(in, s + 12 * g, sizeof in);
    std::uint32_t out[4] = {in[0] | kAlpha, (in[0] >> 24) | (in[1] << 8) | kAlpha,
                            (in[1] >> 16) | (in[2] << 16) | kAlpha, (in[2] >> 8) | kAlpha};
    if constexpr (kBgr) {
      for (std::uint32_t& v : out) v = swap_red_blue(v);
    }
    std::memcpy(d + 16 * g, out, sizeof out);
  }
  for (int x = groups * 4; x < width; ++x) {
    d[4 * x + 0] = s[3 * x + (kBgr ? 2 : 0)];
    d[4 * x + 1] = s[3 * x + 1];
    d[4 * x + 2] = s[3 * x + (kBgr ? 0 : 2)];
    d[4 * x + 3] = 255;
  }
}

// Top-down frame -> bottom-up RGBA (GL's row order).
void convert_rows(const std::uint8_t* src, std::uint8_t* dst, int width, int height, bool bgr) {
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* s = src + static_cast<std::size_t>(height - 1 - y) * width * 3;
    std::uint8_t* d = dst + static_cast<std::size_t>(y) * width * 4;
    if (bgr) {
      expand_row<true>(s, d, width);
    } else {
      expand_row<false>(s, d, width);
    }
  }
}

}  // namespace

Result<VideoBackground> VideoBackground::create(int width, int height) {
  if (width <= 0 || height <= 0) {
    return Error{"video background: frame size " + core::to_string(core::ImageSize{width, height}) +
                 " is empty"};
  }
  auto program =
      Program::link(shaders::kBackgroundVertex, shaders::kBackgroundFragment, "background");
  if (!program) return program.error();
  VideoBackground b;
  b.program_ = std::move(program.value());
  b.texture_ = Texture::create_2d(width, height, GL_RGBA8);
  b.vao_ = VertexArray::create();
  b.staging_.resize(static_cast<std::size_t>(width) * height * 4);
  GLint previous_read = 0;
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &previous_read);
  b.framebuffer_ = Framebuffer::create();
  b.framebuffer_.bind(GL_READ_FRAMEBUFFER);
  glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, b.texture_.id(),
                         0);
  const GLenum status = glCheckFramebufferStatus(GL_READ_FRAMEBUFFER);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(previous_read));
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    return Error{"video background: framebuffer incomplete (status " + std::to_string(status) +
                 ")"};
  }
  b.program_.use();
  glUniform1i(b.program_.uniform_location("u_frame"), 0);
  return b;
}

void VideoBackground::upload(const std::uint8_t* pixels, ChannelOrder order) {
  assert(texture_ && "VideoBackground::upload(): not created");
  convert_rows(pixels, staging_.data(), width(), height(), order == ChannelOrder::kBgr);
  texture_.upload(GL_RGBA, GL_UNSIGNED_BYTE, staging_.data());
}

void VideoBackground::upload_planes(const core::YCbCrImage& planes) {
  assert(texture_ && "VideoBackground::upload_planes(): not created");
  assert(planes.width == width() && planes.height == height() &&
         "VideoBackground::upload_planes(): the frame must have the background's size");
  if (!ycbcr_program_) {
    auto program =
        Program::link(shaders::kBackgroundVertex, shaders::kYCbCrFragment, "ycbcr background");
    assert(program && "VideoBackground: the Y'CbCr program does not link");
    if (!program) return;
    ycbcr_program_ = std::move(program.value());
    ycbcr_program_.use();
    glUniform1i(ycbcr_program_.uniform_location("u_y"), 0);
    glUniform1i(ycbcr_program_.uniform_location("u_cb"), 1);
    glUniform1i(ycbcr_program_.uniform_location("u_cr"), 2);
  }
  if (luma_.width() != planes.width || luma_.height() != planes.height) {
    luma_ = Texture::create_2d(planes.width, planes.height, GL_R8);
  }
  if (cb_.width() != planes.chroma_width || cb_.height() != planes.chroma_height) {
    cb_ = Texture::create_2d(planes.chroma_width, planes.chroma_height, GL_R8);
    cr_ = Texture::create_2d(planes.chroma_width, planes.chroma_height, GL_R8);
  }
  luma_.upload(GL_RED, GL_UNSIGNED_BYTE, planes.y.data());
  cb_.upload(GL_RED, GL_UNSIGNED_BYTE, planes.cb.data());
  cr_.upload(GL_RED, GL_UNSIGNED_BYTE, planes.cr.data());

  GLint previous_draw = 0, previous_program = 0, viewport[4] = {0, 0, 0, 0};
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous_draw);
  glGetIntegerv(GL_CURRENT_PROGRAM, &previous_program);
  glGetIntegerv(GL_VIEWPORT, viewport);
  framebuffer_.bind(GL_DRAW_FRAMEBUFFER);
  glViewport(0, 0, width(), height());
  ycbcr_program_.use();
  glUniform2f(ycbcr_program_.uniform_location("u_chroma_scale"),
              static_cast<float>(planes.width) /
                  static_cast<float>(core::chroma_factor(planes.width, planes.chroma_width) *
                                     planes.chroma_width),
              static_cast<float>(planes.height) /
                  static_cast<float>(core::chroma_factor(planes.height, planes.chroma_height) *
                                     planes.chroma_height));
  luma_.bind(GL_TEXTURE0);
  cb_.bind(GL_TEXTURE1);
  cr_.bind(GL_TEXTURE2);
  glActiveTexture(GL_TEXTURE0);
  const GLboolean depth = glIsEnabled(GL_DEPTH_TEST), blend = glIsEnabled(GL_BLEND);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  vao_.bind();
  glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
  glBindVertexArray(0);
  if (depth) glEnable(GL_DEPTH_TEST);
  if (blend) glEnable(GL_BLEND);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(previous_draw));
  glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
  glUseProgram(static_cast<GLuint>(previous_program));
}

void VideoBackground::draw() const {
  GLint viewport[4] = {0, 0, 0, 0};
  glGetIntegerv(GL_VIEWPORT, viewport);
  GLint draw_samples = 0;
  glGetIntegerv(GL_SAMPLE_BUFFERS, &draw_samples);
  if (draw_samples == 0) {
    GLint previous_read = 0;
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &previous_read);
    framebuffer_.bind(GL_READ_FRAMEBUFFER);
    const bool unscaled = viewport[2] == width() && viewport[3] == height();
    glBlitFramebuffer(0, 0, width(), height(), viewport[0], viewport[1], viewport[0] + viewport[2],
                      viewport[1] + viewport[3], GL_COLOR_BUFFER_BIT,
                      unscaled ? GL_NEAREST : GL_LINEAR);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(previous_read));
    return;
  }
  program_.use();
  texture_.bind(GL_TEXTURE0);
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  vao_.bind();
  glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
  glBindVertexArray(0);
  glDepthMask(GL_TRUE);
  glEnable(GL_DEPTH_TEST);
}

}  // namespace telear::render
