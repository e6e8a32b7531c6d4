#pragma once
// The simulated stereo rig: two TRUE cameras (intrinsics, Brown-Conrady distortion, image
// size) mounted at a true pose relative to the robot base. It is the ground truth against
// which calibration and registration are measured (docs/simulation.md, "Stereo rig").
//
// Rig frame (OpenCV camera convention, like each camera): origin midway between the two
// optical centres, x towards the right camera, y down in the images, z forward along the
// (parallel) optical axes. With the rig's pose T_base_rig and baseline b:
//
//   T_base_cam_left  = T_base_rig * Translation(-b/2, 0, 0)
//   T_base_cam_right = T_base_rig * Translation(+b/2, 0, 0)
//   camera.T_cam_base = T_base_cam^-1              (p_cam = T_cam_base p_base)
//
// The pose is written as a look-at (centre, target, up): z_rig = unit(target - centre),
// x_rig = unit(z_rig x up), y_rig = z_rig x x_rig (so `up` shows upwards in the images).
//
// File (YAML, data/rigs/*.yaml; paths relative to the file):
//   name: puma560_rig
//   robot: puma560                       # robot name or file, for load_robot
//   body: ../robots/puma560.real.body.yaml   # optional: the real arm's look
//   baseline_m: 0.06                     # optional, default 0.06 (the seed's rig)
//   pose: {centre_m: [x, y, z], look_at_m: [x, y, z], up: [0, 0, 1]}
//   cameras:
//     left:  {image_size: [640, 480], fc: [fx, fy], cc: [cx, cy], alpha_c: 0, kc: [5 values]}
//     right: {...}
// Untrusted input: every error names the file and the field.

#include <Eigen/Geometry>
#include <optional>
#include <string>

#include "telear/core/marker_mount.hpp"
#include "telear/core/result.hpp"
#include "telear/core/workspace.hpp"
#include "telear/vision/camera_model.hpp"

namespace telear::sim {

enum class Eye { kLeft, kRight };

struct StereoRig {
  std::string name;
  std::string robot;      // as given to load_robot (resolved to a path when it is a file)
  std::string body_file;  // resolved path, empty: the robot's own body
  // The scene around the robot (the table, the box to pick): resolved path and contents;
  // empty: nothing but the floor.
  std::string workspace_file;
  core::Workspace workspace;
  // The registration marker on the flange: resolved path and contents; empty: the robot's
  // own marker file (core::marker_mount_for), looked up by the scene renderer.
  std::string marker_file;
  std::optional<core::MarkerMount> marker;
  double baseline_m = 0.06;
  Eigen::Isometry3d T_base_rig = Eigen::Isometry3d::Identity();
  vision::StereoCameraModel cameras;  // true cameras, T_cam_base set from the rig pose

  const vision::CameraModel& camera(Eye eye) const {
    return eye == Eye::kLeft ? cameras.left : cameras.right;
  }
  // Pose of the rig frame from a look-at (centre != target, up not parallel to the view).
  static Eigen::Isometry3d look_at(const Eigen::Vector3d& centre_base,
                                   const Eigen::Vector3d& target_base,
                                   const Eigen::Vector3d& up_base);
  // Sets both cameras' T_cam_base from T_base_rig and baseline_m.
  void update_camera_poses();
};

Result<StereoRig> parse_stereo_rig_yaml(const std::string& text, const std::string& source,
                                        const std::string& base_directory);
Result<StereoRig> load_stereo_rig(const std::string& path);

// The shipped rig of a robot: <data>/rigs/<robot>_rig.yaml.
std::string default_rig_file(const std::string& robot_name = "puma560");

}  // namespace telear::sim
