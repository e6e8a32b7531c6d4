#include "telear/sim/grasp_model.hpp"

#include <algorithm>

namespace telear::sim {

GraspModel::GraspModel(const WorkspaceObject& object, GraspModelOptions options)
    : object_(object),
      options_(options),
      T_base_object_(Eigen::Isometry3d(Eigen::Translation3d(object.centre_base))) {}

void GraspModel::update(const Eigen::Isometry3d& T_base_grip, double opening_m) {
  const bool closed_on_box = opening_m <= object_.edge_m + options_.grip_slack_m;
  if (!held_) {
    const double distance = (T_base_grip.translation() - T_base_object_.translation()).norm();
    if (closed_on_box && distance <= options_.capture_distance_m) {
      held_ = true;
      ++grasps_;
      T_grip_object_ = T_base_grip.inverse() * T_base_object_;
    }
  } else if (!closed_on_box) {
    held_ = false;
    Eigen::Vector3d centre = T_base_object_.translation();
    centre.z() = support_z(centre) + object_.edge_m / 2;
    T_base_object_.translation() = centre;
  }
  if (held_) T_base_object_ = T_base_grip * T_grip_object_;
}

double GraspModel::rendered_opening(double opening_m) const {
  return held_ ? std::max(opening_m, object_.edge_m) : opening_m;
}

double GraspModel::support_z(const Eigen::Vector3d& centre) const {
  const Eigen::Vector2d offset = centre.head<2>() - options_.table_centre_m;
  const bool over_table = std::abs(offset.x()) <= options_.table_size_m.x() / 2 &&
                          std::abs(offset.y()) <= options_.table_size_m.y() / 2;
  return over_table && centre.z() >= options_.table_top_z_m ? options_.table_top_z_m : 0.0;
}

}  // namespace telear::sim
