#pragma once
// Whether a camera will see the flange's target at a joint configuration, decided before the
// arm goes there (the automatic capture poses, registration_capture.hpp). A pose the detector
// cannot use costs a move and gives nothing, and a marker half hidden gives wrong corners, so
// a candidate pose is kept only when, in that camera:
//
//   1. the target faces it: the angle between the target's normal and the line to the camera
//      centre is below max_view_angle_deg (beyond it the 4x4 cells are too foreshortened);
//   2. its four corners project at least margin_px inside the image (a marker's black square;
//      a ChArUco board's chessboard, all of it, so that every corner can be found), and a
//      cell of its markers spans at least min_cell_px each way at its centre: the decoder
//      reads the cells, and a small board's markers seen obliquely are unreadable first;
//   3. nothing is in the way: the sight lines from the marker to the camera centre miss every
//      triangle of the arm's own body at that configuration (its links, gripper fingers and
//      moving parts, core::ArmBody) and of the workspace's objects (the table, the box).
//      The sight lines start 2 cm in front of a grid over the target and the inner part of
//      its quiet zone (sight_scale times the target's half size from its centre: the white
//      border the detector needs), which also leaves room for a real arm a little larger
//      than its nominal body. The grid is 3 x 3 for a marker; a board's points are at most a
//      square apart, so that no link stands between two lines and hides a few corners.
//
// The target sits where the robot's marker mount says (its pose on the flange); it is the
// mount's own ArUco marker unless another (vision::RegistrationTarget) is given.
//
// The body is the robot's nominal one (the robot's body file or URDF visuals), not the
// simulator's "real" body: this is what a lab knows about its own arm.

#include <Eigen/Geometry>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "telear/core/arm_body.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/marker_mount.hpp"
#include "telear/core/robot_model.hpp"
#include "telear/core/workspace.hpp"
#include "telear/vision/camera_model.hpp"
#include "telear/vision/registration_target.hpp"

namespace telear::session {

struct MarkerVisibilityOptions {
  double margin_px = 30.0;           // corners this far inside the image
  double max_view_angle_deg = 50.0;  // the marker faces the camera within this
  double sight_scale = 1.2;          // sight lines from this many half sides out (quiet zone)
  double min_cell_px = 1.5;          // a marker cell's projected size, both ways
};

class MarkerVisibility {
 public:
  // `body`: the arm's body (null: no test against the arm); `workspace`: the objects around
  // the robot (null: none). Both are copied as triangles; the model must outlive this object.
  // `target`: what the mount carries (unset: its marker).
  MarkerVisibility(const core::RobotModel& model, const core::MarkerMount& marker,
                   const core::ArmBody* body, const core::Workspace* workspace,
                   const MarkerVisibilityOptions& options = {},
                   const std::optional<vision::RegistrationTarget>& target = std::nullopt);

  // Empty when `camera` sees the whole target at q; else why not: "faces away (63 deg)",
  // "outside the image", "cells of 1.2 px", "hidden by link3" (a body part's or workspace
  // object's name).
  std::string hidden_reason(const vision::CameraModel& camera, const Eigen::VectorXd& q);
  bool visible(const vision::CameraModel& camera, const Eigen::VectorXd& q) {
    return hidden_reason(camera, q).empty();
  }

  // The target's pose in the base frame at the configuration of the last call (or q).
  Eigen::Isometry3d marker_pose(const Eigen::VectorXd& q);

  int occluder_count() const { return static_cast<int>(occluders_.size()); }

 private:
  struct Occluder {
    std::string name;
    int link = -1;  // -1: fixed in the base frame (workspace)
    Eigen::Isometry3d T_link_part = Eigen::Isometry3d::Identity();
    std::vector<Eigen::Vector3d> triangles;            // 3 per triangle, part frame
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // bounding sphere, part frame
    double radius = 0.0;
  };
  static bool segment_hits(const Occluder& occluder, const Eigen::Vector3d& a,
                           const Eigen::Vector3d& b);

  const core::RobotModel& model_;
  core::MarkerMount marker_;
  MarkerVisibilityOptions options_;
  core::KinematicsData data_;
  std::vector<Occluder> occluders_;
  std::array<Eigen::Vector3d, 4> corners_;     // target frame: what must be inside the image
  double cell_m_ = 0.0;                        // one cell of the target's markers
  std::vector<Eigen::Vector3d> sight_points_;  // target frame
};

}  // namespace telear::session
