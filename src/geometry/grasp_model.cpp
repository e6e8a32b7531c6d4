#include "telear/geometry/grasp_model.hpp"

#include <algorithm>

namespace telear::geometry {

Result<GraspModel> GraspModel::create(core::Workspace workspace, GraspModelOptions options) {
  const core::WorkspaceObject* object = workspace.first_graspable();
  if (!object) {
    return Error{"the workspace " + (workspace.source.empty() ? workspace.name : workspace.source) +
                 " has no graspable object (mark one `graspable: true`)"};
  }
  GraspModel grasp;
  const Eigen::Vector3d half = object->half_extent_base();
  grasp.width_m_ = 2.0 * std::min(half.x(), half.y());
  grasp.half_height_m_ = half.z();
  grasp.T_base_object_ = object->T_base_object;
  grasp.workspace_ = std::move(workspace);
  grasp.options_ = options;
  return grasp;
}

void GraspModel::update(const Eigen::Isometry3d& T_base_grip, double opening_m) {
  const bool closed_on_object = opening_m <= width_m_ + options_.grip_slack_m;
  if (!held_) {
    const double distance = (T_base_grip.translation() - T_base_object_.translation()).norm();
    if (closed_on_object && distance <= options_.capture_distance_m) {
      held_ = true;
      ++grasps_;
      T_grip_object_ = T_base_grip.inverse() * T_base_object_;
    }
  } else if (!closed_on_object) {
    held_ = false;
    Eigen::Vector3d centre = T_base_object_.translation();
    centre.z() = workspace_.support_height(centre.head<2>(), centre.z()) + half_height_m_;
    T_base_object_.translation() = centre;
  }
  if (held_) T_base_object_ = T_base_grip * T_grip_object_;
}

double GraspModel::rendered_opening(double opening_m) const {
  return held_ ? std::max(opening_m, width_m_) : opening_m;
}

}  // namespace telear::geometry
