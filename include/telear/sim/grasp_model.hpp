#pragma once
// The box on the table, picked and placed: just enough physics for a pick-and-place demo to
// look right in the simulated video.
//
// The box is grasped when the gripper closes on it: the finger gap shrinks to the box's edge
// (plus `grip_slack_m`) while the gripper's centre (between the fingers) is within
// `capture_distance_m` of the box's centre. From then on the box moves rigidly with the
// gripper (T_grip_object fixed at the grasp). When the gap opens past the edge again the box
// is released and drops straight down onto what is under it: the table top where its centre
// is over the table, otherwise the floor (z = 0), keeping its orientation.
//
// While held, the fingers cannot close further than the box: rendered_opening() clamps the
// gap to the edge so the fingers touch the box instead of passing through it.

#include <Eigen/Geometry>

#include "telear/sim/scene_renderer.hpp"

namespace telear::sim {

struct GraspModelOptions {
  double capture_distance_m = 0.02;
  double grip_slack_m = 0.002;
  // The table top (base frame): centre, size, height of its upper face.
  Eigen::Vector2d table_centre_m{0.55, -0.45};
  Eigen::Vector2d table_size_m{0.5, 0.7};
  double table_top_z_m = 0.40;
};

class GraspModel {
 public:
  explicit GraspModel(const WorkspaceObject& object = SceneRenderer::workspace_object(),
                      GraspModelOptions options = {});

  // One step: the gripper's centre frame (base frame) and the finger gap (m).
  void update(const Eigen::Isometry3d& T_base_grip, double opening_m);

  bool held() const { return held_; }
  const Eigen::Isometry3d& T_base_object() const { return T_base_object_; }
  double rendered_opening(double opening_m) const;
  int grasps() const { return grasps_; }

 private:
  double support_z(const Eigen::Vector3d& centre) const;

  WorkspaceObject object_;
  GraspModelOptions options_;
  Eigen::Isometry3d T_base_object_;
  Eigen::Isometry3d T_grip_object_ = Eigen::Isometry3d::Identity();
  bool held_ = false;
  int grasps_ = 0;
};

}  // namespace telear::sim
