#include "telear/render/stereo_composer.hpp"

#include <cassert>

namespace telear::render {
namespace {

// A full-screen triangle; v_uv spans [0, 1] over the viewport. Eye textures are GL bottom-up
// like the framebuffer, so no flip.
const char* const kComposeVertex = R"glsl(#version 330 core
out vec2 v_uv;
void main() {
  vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
  v_uv = (p + 1.0) * 0.5;
  gl_Position = vec4(p, 0.0, 1.0);
}
)glsl";

const char* const kComposeFragment = R"glsl(#version 330 core
in vec2 v_uv;
uniform sampler2D u_eye;
uniform int u_mode;  // 0 copy, 1 anaglyph left (red = luminance), 2 anaglyph right (cyan)
out vec4 frag_colour;
void main() {
  vec3 c = texture(u_eye, v_uv).rgb;
  if (u_mode == 1) c = vec3(dot(c, vec3(0.299, 0.587, 0.114)), 0.0, 0.0);
  frag_colour = vec4(c, 1.0);
}
)glsl";

}  // namespace

Result<StereoLayout> parse_stereo_layout(const std::string& name) {
  if (name == "sbs") return StereoLayout::kSideBySide;
  if (name == "tb") return StereoLayout::kTopBottom;
  if (name == "anaglyph") return StereoLayout::kAnaglyph;
  if (name == "separate") return StereoLayout::kSeparate;
  return Error{"unknown stereo layout '" + name + "' (use sbs, tb, anaglyph or separate)"};
}

const char* stereo_layout_name(StereoLayout layout) {
  switch (layout) {
    case StereoLayout::kSideBySide:
      return "sbs";
    case StereoLayout::kTopBottom:
      return "tb";
    case StereoLayout::kAnaglyph:
      return "anaglyph";
    case StereoLayout::kSeparate:
      return "separate";
  }
  return "?";
}

ComposedSize composed_size(StereoLayout layout, int eye_width, int eye_height) {
  switch (layout) {
    case StereoLayout::kSideBySide:
      return {2 * eye_width, eye_height};
    case StereoLayout::kTopBottom:
      return {eye_width, 2 * eye_height};
    case StereoLayout::kAnaglyph:
    case StereoLayout::kSeparate:
      return {eye_width, eye_height};
  }
  return {eye_width, eye_height};
}

WindowStereo choose_window_stereo(bool stereo_granted) {
  if (stereo_granted) return {true, StereoLayout::kSideBySide, ""};
  return {false, StereoLayout::kSideBySide,
          "quad-buffer stereo is not available (the GL driver offers no stereo visual); "
          "showing the two eyes side by side instead"};
}

Result<StereoComposer> StereoComposer::create() {
  auto program = Program::link(kComposeVertex, kComposeFragment, "stereo composer");
  if (!program) return program.error();
  StereoComposer c;
  c.program_ = std::move(program.value());
  c.program_.use();
  glUniform1i(c.program_.uniform_location("u_eye"), 0);
  c.u_mode_ = c.program_.uniform_location("u_mode");
  c.vao_ = VertexArray::create();
  return c;
}

void StereoComposer::draw_eye(const Texture& eye, int mode) const {
  glUniform1i(u_mode_, mode);
  eye.bind(GL_TEXTURE0);
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

void StereoComposer::compose(StereoLayout layout, const Texture& left, const Texture& right,
                             const OffscreenTarget& out) const {
  assert(out.width() == composed_size(layout, left.width(), left.height()).width &&
         out.height() == composed_size(layout, left.width(), left.height()).height &&
         "StereoComposer::compose(): output size does not match the layout");
  compose_into(layout, left, right, out.framebuffer_id(), out.width(), out.height());
}

void StereoComposer::compose_into(StereoLayout layout, const Texture& left, const Texture& right,
                                  GLuint framebuffer, int width, int height) const {
  assert(program_ && "StereoComposer::compose_into(): not created");
  assert(layout != StereoLayout::kSeparate &&
         "StereoComposer::compose_into(): kSeparate has nothing to compose");
  assert(left.width() == right.width() && left.height() == right.height());
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  program_.use();
  vao_.bind();
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  switch (layout) {
    case StereoLayout::kSideBySide:
      glViewport(0, 0, width / 2, height);
      draw_eye(left, 0);
      glViewport(width / 2, 0, width - width / 2, height);
      draw_eye(right, 0);
      break;
    case StereoLayout::kTopBottom:
      // GL rows go up: the top half starts at height / 2.
      glViewport(0, height / 2, width, height - height / 2);
      draw_eye(left, 0);
      glViewport(0, 0, width, height / 2);
      draw_eye(right, 0);
      break;
    case StereoLayout::kAnaglyph:
      glViewport(0, 0, width, height);
      glColorMask(GL_TRUE, GL_FALSE, GL_FALSE, GL_TRUE);
      draw_eye(left, 1);
      glColorMask(GL_FALSE, GL_TRUE, GL_TRUE, GL_FALSE);
      draw_eye(right, 2);
      glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
      break;
    case StereoLayout::kSeparate:
      break;
  }
  glBindVertexArray(0);
  glEnable(GL_DEPTH_TEST);
}

Status StereoComposer::present_page_flipped(GlContext& context, const Texture& left,
                                            const Texture& right, int width, int height) const {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  GLboolean stereo = GL_FALSE;
  glGetBooleanv(GL_STEREO, &stereo);
  if (stereo != GL_TRUE) {
    return Error{"page-flipped stereo: the context (" + context.description() +
                 ") has no quad-buffer stereo visual"};
  }
  program_.use();
  vao_.bind();
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glViewport(0, 0, width, height);
  glDrawBuffer(GL_BACK_LEFT);
  draw_eye(left, 0);
  glDrawBuffer(GL_BACK_RIGHT);
  draw_eye(right, 0);
  glDrawBuffer(GL_BACK);
  glBindVertexArray(0);
  glEnable(GL_DEPTH_TEST);
  context.swap_buffers();
  return Status::Ok();
}

}  // namespace telear::render
