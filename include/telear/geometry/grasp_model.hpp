#pragma once
// The graspable object of the workspace (the box on the table), picked and placed: just
// enough physics for a pick-and-place demo to look right in the simulated video, and the one
// decision of what the gripper holds for collision checking (telear/geometry/carried_objects.hpp:
// the session's validation and the robot server's guard). It lives in geometry, not sim,
// because the robot server (net) checks carried objects without linking the simulator.
//
// The object is grasped when the gripper closes on it: the finger gap shrinks to its width
// (the smaller horizontal edge of its bounds, plus `grip_slack_m`) while the gripper's centre
// (between the fingers) is within `capture_distance_m` of the object's centre. From then on
// it moves rigidly with the gripper (T_grip_object fixed at the grasp). When the gap opens
// past the width again it is released and drops straight down onto what is under it (the
// workspace's support height: a table top where it is over the table, otherwise the floor,
// z = 0), keeping its orientation.
//
// While held, the fingers cannot close further than the object: rendered_opening() clamps
// the gap to its width so the fingers touch it instead of passing through it.

#include <Eigen/Geometry>

#include "telear/core/result.hpp"
#include "telear/core/workspace.hpp"

namespace telear::geometry {

struct GraspModelOptions {
  double capture_distance_m = 0.02;
  double grip_slack_m = 0.002;
};

class GraspModel {
 public:
  GraspModel() = default;
  // The workspace's first graspable object is the one picked. Errors: the workspace has none.
  static Result<GraspModel> create(core::Workspace workspace, GraspModelOptions options = {});

  // One step: the gripper's centre frame (base frame) and the finger gap (m).
  void update(const Eigen::Isometry3d& T_base_grip, double opening_m);

  bool held() const { return held_; }
  const Eigen::Isometry3d& T_base_object() const { return T_base_object_; }
  double rendered_opening(double opening_m) const;
  int grasps() const { return grasps_; }
  // The object's grip width (m) and half height (m, its centre above a support).
  double width_m() const { return width_m_; }

 private:
  core::Workspace workspace_;
  GraspModelOptions options_;
  double width_m_ = 0.0, half_height_m_ = 0.0;
  Eigen::Isometry3d T_base_object_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d T_grip_object_ = Eigen::Isometry3d::Identity();
  bool held_ = false;
  int grasps_ = 0;
};

}  // namespace telear::geometry
