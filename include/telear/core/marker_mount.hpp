#pragma once
// The registration marker mounted on the robot's flange: which ArUco marker it is, how big,
// and where it sits on the last link. The simulated rig draws it there, the live
// registration check detects it and compares its corners with forward kinematics, so both
// read it from one file beside the robot (data/robots/NAME.marker.yaml, docs/registration.md):
//
//   dictionary: DICT_4X4_50      # OpenCV's predefined ArUco dictionary (the only one today)
//   id: 0                        # 0..49
//   side_m: 0.1                  # the black square's side (the detector's corners)
//   pose_in_flange: {xyz: [0.05, 0.0, 0.07], rpy: [1.5707963267948966, 0, 1.5707963267948966]}
//
// Marker frame (OpenCV's aruco convention): origin at the marker's centre, x to the right and
// y up as the marker image is printed, z out of the face towards the viewer. Corner k, in the
// order cv::aruco::detectMarkers returns them (top-left, top-right, bottom-right, bottom-left
// of the printed image): (-L/2, L/2, 0), (L/2, L/2, 0), (L/2, -L/2, 0), (-L/2, -L/2, 0).

#include <Eigen/Geometry>
#include <array>
#include <string>

#include "telear/core/result.hpp"
#include "telear/core/robot_model.hpp"

namespace telear::core {

struct MarkerMount {
  std::string dictionary = "DICT_4X4_50";
  int id = 0;
  double side_m = 0.1;
  Eigen::Isometry3d T_flange_marker = Eigen::Isometry3d::Identity();

  // The four detector corners in the flange frame (order as above).
  std::array<Eigen::Vector3d, 4> corners_flange() const;
};

// Errors name the source and the field: unknown keys, a dictionary other than DICT_4X4_50, an
// id outside 0..49, a side that is not positive, a malformed pose.
Result<MarkerMount> parse_marker_mount_yaml(const std::string& text, const std::string& source);
Result<MarkerMount> load_marker_mount_file(const std::string& path);

// The robot's marker file: NAME.marker.yaml beside the robot's file, else in the data
// directory's robots/ folder. Errors: no such file (naming where it was looked for).
Result<MarkerMount> marker_mount_for(const RobotModel& model);

}  // namespace telear::core
