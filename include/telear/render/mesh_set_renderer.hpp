#pragma once
// The GPU side of the seed's per-link data structure: a set of meshes ("parts"), each with
// its own vertex array / vertex buffer / index buffer, uploaded ONCE, each drawn with its own
// model matrix T_base_part. The matrices live in one uniform buffer (std140, mat4 per part):
// set_matrices() uploads only the parts that changed; a draw uploads nothing but the camera.
//
// Vertex shader, per part k:  gl_Position = projection * T_view_base * T_base_part[k] * p.
// Conventions of projection / T_view_base: telear/render/view_math.hpp (OpenCV camera frame).
// Every method but the default constructor needs the creating context current.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "telear/core/arm_body_pose.hpp"
#include "telear/core/mesh.hpp"
#include "telear/core/result.hpp"
#include "telear/render/draw_options.hpp"
#include "telear/render/gl_objects.hpp"

namespace telear::render {

class MeshSetRenderer {
 public:
  // Parts per set (the uniform block is sized for this: 64 * 64 B = 4 KiB).
  static constexpr int kMaxParts = 64;

  MeshSetRenderer() = default;
  // Uploads every mesh (an empty mesh is a part that draws nothing); matrices start at
  // identity. Errors: more than kMaxParts meshes, or the shaders fail to build.
  static Result<MeshSetRenderer> create(const std::vector<const core::Mesh*>& meshes);

  int part_count() const { return static_cast<int>(parts_.size()); }
  std::size_t triangle_count() const { return triangle_count_; }
  std::size_t line_count() const { return line_count_; }

  // Uploads matrices[range.first .. range.end()) (one glBufferSubData); `matrices` holds
  // part_count() matrices. Returns the number of matrices uploaded.
  int set_matrices(const std::vector<Eigen::Matrix4f>& matrices, core::PartRange range);
  void set_matrix(int part, const Eigen::Matrix4f& T_base_part);

  // Draws every part into the bound framebuffer / viewport with depth testing (enabled here,
  // GL_LESS); back-face culling and blending (a ghost) are enabled as the options say and
  // disabled again afterwards.
  void draw(const Eigen::Matrix4f& projection, const Eigen::Matrix4f& T_view_base,
            const DrawOptions& options = {}) const;

 private:
  struct Part {
    VertexArray vao;
    Buffer vertices;
    Buffer indices;  // triangles, then lines
    GLsizei triangle_indices = 0;
    GLsizei line_indices = 0;
  };
  void draw_parts(bool lines, const DrawOptions& options) const;

  std::vector<Part> parts_;
  Buffer matrices_;  // uniform buffer, kMaxParts mat4
  Program program_;
  GLint u_projection_ = -1, u_T_view_base_ = -1, u_part_ = -1, u_lit_ = -1;
  GLint u_light_dir_view_ = -1, u_ambient_ = -1, u_diffuse_ = -1, u_alpha_ = -1;
  GLint u_use_colour_ = -1, u_colour_ = -1;
  std::size_t triangle_count_ = 0;
  std::size_t line_count_ = 0;
};

}  // namespace telear::render
