#include "telear/render/mesh_set_renderer.hpp"

#include <algorithm>

#include <cassert>
#include <cstddef>

#include "telear/render/shaders.hpp"

namespace telear::render {
namespace {

constexpr GLsizeiptr kMat4Bytes = 16 * sizeof(float);

}  // namespace

Result<MeshSetRenderer> MeshSetRenderer::create(const std::vector<const core::Mesh*>& meshes) {
  if (static_cast<int>(meshes.size()) > kMaxParts) {
    return Error{"a mesh set holds at most " + std::to_string(kMaxParts) + " parts, got " +
                 std::to_string(meshes.size())};
  }
  auto program = Program::link(shaders::kSurfaceVertex, shaders::kSurfaceFragment, "surface");
  if (!program) return program.error();

  MeshSetRenderer r;
  r.program_ = std::move(program.value());
  const GLuint id = r.program_.id();
  const GLuint block = glGetUniformBlockIndex(id, "Parts");
  assert(block != GL_INVALID_INDEX && "MeshSetRenderer: the surface shader has no Parts block");
  glUniformBlockBinding(id, block, shaders::kPartsBinding);
  r.u_projection_ = r.program_.uniform_location("u_projection");
  r.u_T_view_base_ = r.program_.uniform_location("u_T_view_base");
  r.u_part_ = r.program_.uniform_location("u_part");
  r.u_lit_ = r.program_.uniform_location("u_lit");
  r.u_light_dir_view_ = r.program_.uniform_location("u_light_dir_view");
  r.u_ambient_ = r.program_.uniform_location("u_ambient");
  r.u_diffuse_ = r.program_.uniform_location("u_diffuse");
  r.u_alpha_ = r.program_.uniform_location("u_alpha");
  r.u_use_colour_ = r.program_.uniform_location("u_use_colour");
  r.u_colour_ = r.program_.uniform_location("u_colour");

  // All kMaxParts matrices exist in the block; the unused ones stay identity.
  std::vector<Eigen::Matrix4f> identity(kMaxParts, Eigen::Matrix4f::Identity());
  r.matrices_ = Buffer::create();
  r.matrices_.set_data(GL_UNIFORM_BUFFER, kMaxParts * kMat4Bytes, identity.data(), GL_DYNAMIC_DRAW);

  for (const core::Mesh* mesh : meshes) {
    assert(mesh != nullptr && "MeshSetRenderer::create(): null mesh");
    Part part;
    part.triangle_indices = static_cast<GLsizei>(mesh->triangles.size());
    part.line_indices = static_cast<GLsizei>(mesh->lines.size());
    r.triangle_count_ += mesh->triangle_count();
    r.line_count_ += mesh->line_count();
    if (!mesh->vertices.empty()) {
      part.vao = VertexArray::create();
      part.vao.bind();
      part.vertices = Buffer::create();
      part.vertices.set_data(
          GL_ARRAY_BUFFER,
          static_cast<GLsizeiptr>(mesh->vertices.size() * sizeof(core::MeshVertex)),
          mesh->vertices.data(), GL_STATIC_DRAW);
      std::vector<std::uint32_t> indices(mesh->triangles);
      indices.insert(indices.end(), mesh->lines.begin(), mesh->lines.end());
      part.indices = Buffer::create();
      // The element buffer binding is VAO state: bound while the VAO is.
      part.indices.set_data(GL_ELEMENT_ARRAY_BUFFER,
                            static_cast<GLsizeiptr>(indices.size() * sizeof(std::uint32_t)),
                            indices.data(), GL_STATIC_DRAW);
      const auto stride = static_cast<GLsizei>(sizeof(core::MeshVertex));
      glEnableVertexAttribArray(0);
      glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride,
                            reinterpret_cast<const void*>(offsetof(core::MeshVertex, position)));
      glEnableVertexAttribArray(1);
      glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride,
                            reinterpret_cast<const void*>(offsetof(core::MeshVertex, normal)));
      glEnableVertexAttribArray(2);
      glVertexAttribPointer(2, 3, GL_FLOAT, GL_FALSE, stride,
                            reinterpret_cast<const void*>(offsetof(core::MeshVertex, colour)));
      glBindVertexArray(0);
    }
    r.parts_.push_back(std::move(part));
  }
  return r;
}

int MeshSetRenderer::set_matrices(const std::vector<Eigen::Matrix4f>& matrices,
                                  core::PartRange range) {
  assert(static_cast<int>(matrices.size()) >= range.end() && range.first >= 0 &&
         range.end() <= part_count() && "MeshSetRenderer::set_matrices(): range out of bounds");
  if (range.empty()) return 0;
  matrices_.set_sub_data(GL_UNIFORM_BUFFER, range.first * kMat4Bytes, range.count * kMat4Bytes,
                         matrices[static_cast<std::size_t>(range.first)].data());
  return range.count;
}

void MeshSetRenderer::set_matrix(int part, const Eigen::Matrix4f& T_base_part) {
  assert(part >= 0 && part < part_count() && "MeshSetRenderer::set_matrix(): bad part");
  matrices_.set_sub_data(GL_UNIFORM_BUFFER, part * kMat4Bytes, kMat4Bytes, T_base_part.data());
}

void MeshSetRenderer::draw_parts(bool lines, const DrawOptions& options) const {
  for (std::size_t k = 0; k < parts_.size(); ++k) {
    const Part& part = parts_[k];
    const GLsizei count = lines ? part.line_indices : part.triangle_indices;
    if (count == 0) continue;
    glUniform1i(u_part_, static_cast<GLint>(k));
    const bool highlight = std::find(options.highlight_parts.begin(), options.highlight_parts.end(),
                                     static_cast<int>(k)) != options.highlight_parts.end();
    if (highlight) {
      glUniform1i(u_use_colour_, 1);
      glUniform3fv(u_colour_, 1, options.highlight_colour.data());
    } else if (!options.highlight_parts.empty()) {  // back to the set's own colour
      glUniform1i(u_use_colour_, options.colour ? 1 : 0);
      if (options.colour) glUniform3fv(u_colour_, 1, options.colour->data());
    }
    part.vao.bind();
    const std::size_t offset =
        lines ? static_cast<std::size_t>(part.triangle_indices) * sizeof(std::uint32_t) : 0;
    glDrawElements(lines ? GL_LINES : GL_TRIANGLES, count, GL_UNSIGNED_INT,
                   reinterpret_cast<const void*>(offset));
  }
  glBindVertexArray(0);
}

void MeshSetRenderer::draw(const Eigen::Matrix4f& projection, const Eigen::Matrix4f& T_view_base,
                           const DrawOptions& options) const {
  if (parts_.empty()) return;
  program_.use();
  glBindBufferBase(GL_UNIFORM_BUFFER, shaders::kPartsBinding, matrices_.id());
  glUniformMatrix4fv(u_projection_, 1, GL_FALSE, projection.data());
  glUniformMatrix4fv(u_T_view_base_, 1, GL_FALSE, T_view_base.data());
  const Eigen::Vector3f light_view =
      (T_view_base.topLeftCorner<3, 3>() * options.lighting.direction_base).normalized();
  glUniform3fv(u_light_dir_view_, 1, light_view.data());
  glUniform3fv(u_ambient_, 1, options.lighting.ambient.data());
  glUniform3fv(u_diffuse_, 1, options.lighting.diffuse.data());
  glUniform1f(u_alpha_, options.alpha);
  glUniform1i(u_use_colour_, options.colour ? 1 : 0);
  if (options.colour) glUniform3fv(u_colour_, 1, options.colour->data());

  const bool lines = options.style == DrawOptions::Style::kWireframe;
  glUniform1i(u_lit_, lines ? 0 : 1);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  if (options.cull_back_faces && !lines) {
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
  } else {
    glDisable(GL_CULL_FACE);
  }
  if (options.alpha >= 1.0f) {
    draw_parts(lines, options);
    glDisable(GL_CULL_FACE);
    return;
  }
  // Ghost.
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  if (!lines) {
    // Depth of the nearest ghost surface first, then blend only that surface.
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    draw_parts(false, options);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
  }
  draw_parts(lines, options);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
}

}  // namespace telear::render
