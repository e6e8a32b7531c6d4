#pragma once
// Left and right eye views into one output (the seed's stereo display, made portable).
//
// Each eye is rendered into its own OffscreenTarget of the eye's size (w x h); the composer
// draws their colour textures (GL bottom-up, as OffscreenTarget holds them) into the output
// framebuffer:
//   kSideBySide  2w x h : left eye in the left half, right eye in the right half;
//   kTopBottom   w x 2h : left eye in the top half (the seed's "sync-doubling" above/below
//                         format: the left frame is sent first, i.e. on top);
//   kAnaglyph    w x h  : red-cyan, half-colour: red = luminance of the left eye
//                         (0.299 R + 0.587 G + 0.114 B), green and blue = the right eye's;
//   kSeparate    w x h  : no composition; each eye's image is kept (the CLI writes two files).
// Page-flipped (quad-buffer) stereo is a property of a window, not a layout:
// present_page_flipped() draws the left eye into GL_BACK_LEFT and the right eye into
// GL_BACK_RIGHT of a window whose context has a stereo visual, then swaps. Most drivers
// offer none (Mesa never does); choose_window_stereo() then falls back to side-by-side with
// a message that says why.

#include <optional>
#include <string>

#include "telear/core/result.hpp"
#include "telear/render/gl_context.hpp"
#include "telear/render/gl_objects.hpp"
#include "telear/render/offscreen_target.hpp"

namespace telear::render {

enum class StereoLayout { kSideBySide, kTopBottom, kAnaglyph, kSeparate };

// "sbs", "tb", "anaglyph", "separate" (the CLI's names); the error lists them.
Result<StereoLayout> parse_stereo_layout(const std::string& name);
const char* stereo_layout_name(StereoLayout layout);

// Size of the composed output for eyes of eye_width x eye_height (kSeparate: one eye's).
struct ComposedSize {
  int width = 0;
  int height = 0;
};
ComposedSize composed_size(StereoLayout layout, int eye_width, int eye_height);

// How a window shows stereo: page-flipped when the context granted a stereo visual, else
// side-by-side, with a message saying so.
struct WindowStereo {
  bool page_flipped = false;
  StereoLayout fallback = StereoLayout::kSideBySide;
  std::string message;  // empty when page-flipped
};
WindowStereo choose_window_stereo(bool stereo_granted);

class StereoComposer {
 public:
  StereoComposer() = default;
  // Needs a current context.
  static Result<StereoComposer> create();

  // Draws the two eye textures (same size) into `out`, whose size must be
  // composed_size(layout, eye size); layout must not be kSeparate.
  void compose(StereoLayout layout, const Texture& left, const Texture& right,
               const OffscreenTarget& out) const;
  // The same into framebuffer `framebuffer` (0: a window's) of the given size.
  void compose_into(StereoLayout layout, const Texture& left, const Texture& right,
                    GLuint framebuffer, int width, int height) const;

  // Quad-buffer stereo into the CURRENT context's default framebuffer (a window of
  // width x height pixels): left eye into GL_BACK_LEFT, right into GL_BACK_RIGHT, then
  // context.swap_buffers(). Error, drawing nothing, when the context has no stereo visual
  // (GL_STEREO false) -- a headless context never has one.
  Status present_page_flipped(GlContext& context, const Texture& left, const Texture& right,
                              int width, int height) const;

 private:
  // Draws `eye` over the current viewport; mode 0 copy, 1 anaglyph red (left), 2 anaglyph
  // cyan (right).
  void draw_eye(const Texture& eye, int mode) const;

  Program program_;
  VertexArray vao_;
  GLint u_mode_ = -1;
};

}  // namespace telear::render
