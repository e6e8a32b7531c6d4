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
//   workspace: ../workspaces/puma560_table.yaml   # optional: the scene (docs/workspace.md)
//   workspace_error:                     # optional: the real scene against that file
//     xyz: [0.01, 0, 0]                  #   m, base frame, every object (default 0)
//     rpy: [0, 0, 0.02]                  #   rad (default 0)
//     objects:                           #   optional, per object, after the common error
//       box: {xyz: [0.02, 0, 0], rpy: [0, 0, 0]}
//   target: "charuco:5x5:0.06:0.045:4x4_50"  # optional: what the flange carries where its
//                                        #   marker mount sits (default: the mount's marker)
//   baseline_m: 0.06                     # optional, default 0.06 (the seed's rig)
//   pose: {centre_m: [x, y, z], look_at_m: [x, y, z], up: [0, 0, 1]}
//   cameras:
//     left:  {image_size: [640, 480], fc: [fx, fy], cc: [cx, cy], alpha_c: 0, kc: [5 values]}
//     right: {...}
//   (per camera, optional: distortion_model: plumb_bob (default), rational_polynomial or
//   equidistant; kc then holds that model's D vector: 5, 8 or 4 numbers)
// Untrusted input: every error names the file and the field.
//
// Modelling error. The operator's views, plan validation and the robot server read the
// workspace file as it is; the rig renders (and the simulated grasp picks from) the scene as
// it really stands, which a real cell never matches exactly. With workspace_error E (common)
// and E_o (object o's), both in the base frame,
//   T_base_object(real) = E_o * E * T_base_object(file)
// so a pure translation moves every object by that much; a rotation turns the scene about the
// base origin. Unknown objects under `objects:` are refused with their name.

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "telear/core/marker_mount.hpp"
#include "telear/core/result.hpp"
#include "telear/core/workspace.hpp"
#include "telear/vision/camera_model.hpp"

namespace telear::sim {

enum class Eye { kLeft, kRight };

// The real scene's modelling error against the workspace file (rig key workspace_error).
struct WorkspaceError {
  Eigen::Isometry3d common = Eigen::Isometry3d::Identity();        // E, every object
  std::vector<std::pair<std::string, Eigen::Isometry3d>> objects;  // E_o by object name

  bool is_identity() const;
};

// The workspace as it really stands: every object of `file` posed by the error (see above).
// Errors: an object of the error that the workspace does not have.
Result<core::Workspace> apply_workspace_error(const core::Workspace& file,
                                              const WorkspaceError& error);

struct StereoRig {
  std::string name;
  std::string robot;      // as given to load_robot (resolved to a path when it is a file)
  std::string body_file;  // resolved path, empty: the robot's own body
  // The scene around the robot (the table, the box to pick): resolved path and contents;
  // empty: nothing but the floor.
  // `workspace` is what the rig renders: the file's objects posed by workspace_error (the
  // operator's copy is the file itself).
  std::string workspace_file;
  WorkspaceError workspace_error;
  core::Workspace workspace;
  // The registration marker on the flange: resolved path and contents; empty: the robot's
  // own marker file (core::marker_mount_for), looked up by the scene renderer.
  std::string marker_file;
  std::optional<core::MarkerMount> marker;
  // The registration target drawn where the marker mount sits (`target:`, a spec of
  // telear/vision/registration_target.hpp, e.g. "charuco:5x5:0.06:0.045:4x4_50"); empty: the
  // mount's own ArUco marker.
  std::string target;
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
