#include "telear/render/point_markers.hpp"

#include <cassert>
#include <cmath>

namespace telear::render {
namespace {

const char* const kMarkerVertex = R"glsl(#version 330 core
layout(location = 0) in vec3 a_position;
uniform mat4 u_projection;
uniform mat4 u_T_view_base;
uniform vec4 u_viewport;  // x, y, width, height (glViewport)
uniform float u_radius;
flat out vec2 v_centre_window;
void main() {
  vec4 clip = u_projection * u_T_view_base * vec4(a_position, 1.0);
  gl_Position = clip;
  // The viewport transform GL applies, evaluated here so the fragment shader knows where the
  // point really is (the sprite's square snaps to pixels; the profile does not).
  vec2 ndc = clip.xy / clip.w;
  v_centre_window = u_viewport.xy + (ndc * 0.5 + 0.5) * u_viewport.zw;
  gl_PointSize = 2.0 * u_radius + 4.0;
}
)glsl";

const char* const kMarkerFragment = R"glsl(#version 330 core
flat in vec2 v_centre_window;
uniform float u_radius;
uniform vec3 u_colour;
out vec4 frag_colour;
void main() {
  vec2 d = gl_FragCoord.xy - v_centre_window;
  float s = dot(d, d) / (u_radius * u_radius);
  if (s >= 1.0) discard;
  float w = (1.0 - s) * (1.0 - s);
  frag_colour = vec4(u_colour * w, w);
}
)glsl";

}  // namespace

Result<PointMarkers> PointMarkers::create() {
  auto program = Program::link(kMarkerVertex, kMarkerFragment, "point markers");
  if (!program) return program.error();
  PointMarkers m;
  m.program_ = std::move(program.value());
  m.u_projection_ = m.program_.uniform_location("u_projection");
  m.u_T_view_base_ = m.program_.uniform_location("u_T_view_base");
  m.u_viewport_ = m.program_.uniform_location("u_viewport");
  m.u_radius_ = m.program_.uniform_location("u_radius");
  m.u_colour_ = m.program_.uniform_location("u_colour");
  m.vao_ = VertexArray::create();
  m.points_ = Buffer::create();
  m.vao_.bind();
  m.points_.set_data(GL_ARRAY_BUFFER, 0, nullptr, GL_DYNAMIC_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
  glBindVertexArray(0);
  return m;
}

void PointMarkers::draw(const Eigen::Matrix4f& projection, const Eigen::Matrix4f& T_view_base,
                        const std::vector<Eigen::Vector3f>& points_base, float radius_px,
                        const Eigen::Vector3f& colour) const {
  assert(program_ && "PointMarkers::draw(): not created");
  assert(radius_px > 0.0f && radius_px <= 100.0f && "PointMarkers::draw(): radius out of range");
  if (points_base.empty()) return;
  std::vector<float> xyz;
  xyz.reserve(points_base.size() * 3);
  for (const Eigen::Vector3f& p : points_base) xyz.insert(xyz.end(), {p.x(), p.y(), p.z()});
  // The buffer is only read by this draw; the const method re-fills GL state, not members.
  glBindBuffer(GL_ARRAY_BUFFER, points_.id());
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(xyz.size() * sizeof(float)), xyz.data(),
               GL_DYNAMIC_DRAW);

  GLint viewport[4] = {0, 0, 0, 0};
  glGetIntegerv(GL_VIEWPORT, viewport);
  program_.use();
  glUniformMatrix4fv(u_projection_, 1, GL_FALSE, projection.data());
  glUniformMatrix4fv(u_T_view_base_, 1, GL_FALSE, T_view_base.data());
  glUniform4f(u_viewport_, static_cast<float>(viewport[0]), static_cast<float>(viewport[1]),
              static_cast<float>(viewport[2]), static_cast<float>(viewport[3]));
  glUniform1f(u_radius_, radius_px);
  glUniform3fv(u_colour_, 1, colour.data());
  glEnable(GL_PROGRAM_POINT_SIZE);
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  vao_.bind();
  glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(points_base.size()));
  glBindVertexArray(0);
  glDisable(GL_BLEND);
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_PROGRAM_POINT_SIZE);
}

}  // namespace telear::render
