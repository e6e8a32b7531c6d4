#pragma once
// Draws an ArmBody (telear/core/arm_body.hpp) at the pose held by an ArmBodyPose
// (telear/core/arm_body_pose.hpp): one vertex buffer per part, built once in the part's own frame;
// per frame only the matrices of the parts that moved are uploaded.
//
//   ArmBody body = build_arm_body(*body_description_for(model), {.segments_override = 8});
//   ArmBodyPose pose(model, body);
//   auto arm = ArmRenderer::create(body);            // a context must be current
//   pose.set_joint(4, 0.3);                          // frames 5..6 re-computed
//   arm->update(pose);                               // uploads parts 5, 6 and the fingers
//   arm->draw(projection, T_cam_base.matrix(), {});  // conventions: view_math.hpp
//
// Two arms (the ghost and the real robot) are two ArmRenderers, each with its own pose.

#include <Eigen/Core>

#include "telear/core/arm_body.hpp"
#include "telear/core/arm_body_pose.hpp"
#include "telear/core/result.hpp"
#include "telear/render/draw_options.hpp"
#include "telear/render/mesh_set_renderer.hpp"

namespace telear::render {

class ArmRenderer {
 public:
  ArmRenderer() = default;
  // Uploads every part's mesh. Errors as MeshSetRenderer::create.
  static Result<ArmRenderer> create(const core::ArmBody& body);

  // Uploads the matrices of pose.changed() and clears the pose's changes. Returns the range
  // uploaded (empty when nothing moved). pose must belong to the same body.
  core::PartRange update(core::ArmBodyPose& pose);

  void draw(const Eigen::Matrix4f& projection, const Eigen::Matrix4f& T_view_base,
            const DrawOptions& options = {}) const {
    parts_.draw(projection, T_view_base, options);
  }

  int part_count() const { return parts_.part_count(); }
  std::size_t triangle_count() const { return parts_.triangle_count(); }
  std::size_t line_count() const { return parts_.line_count(); }
  // Total matrices uploaded since creation (tests: motion uploads matrices, not vertices).
  long matrices_uploaded() const { return matrices_uploaded_; }

 private:
  MeshSetRenderer parts_;
  long matrices_uploaded_ = 0;
};

}  // namespace telear::render
