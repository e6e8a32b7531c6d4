#pragma once
// Camera files (docs/cameras.md). Two layouts are read, by one parser:
//
// OpenCV FileStorage YAML, what cv::FileStorage writes and telear writes:
//   %YAML:1.0
//   ---
//   image_width: 640
//   image_height: 480
//   camera_matrix: !!opencv-matrix             # 3x3, pixels; [0][1] = skew = alpha_c * fx
//     {rows: 3, cols: 3, dt: d, data: [fx, s, cx, 0, fy, cy, 0, 0, 1]}
//   distortion_coefficients: !!opencv-matrix   # k1, k2, p1, p2, k3 (1x5, 5x1, or 1x4)
//     {rows: 1, cols: 5, dt: d, data: [...]}
//   T_cam_base: !!opencv-matrix                # 4x4 row-major, metres: p_cam = T p_base
//     {rows: 4, cols: 4, dt: d, data: [...]}
//
// ROS camera_info YAML (camera_calibration_parsers): image_width, image_height, camera_name,
// camera_matrix {rows, cols, data}, distortion_model (plumb_bob or rational_polynomial),
// distortion_coefficients, rectification_matrix, projection_matrix. The last two describe
// a rectified stereo pair and are ignored: telear renders through K and the distortion.
//
// A stereo file holds the per-camera keys in a `left:` and a `right:` map; a stereo pair can
// also come as two mono files. T_cam_base is optional in either layout (a camera calibrated
// but not yet registered to the robot): without it the pose is the identity and has_pose is
// false. Extra coefficients beyond k3 (8-, 12- or 14-element vectors) must be zero.
//
// Every malformed input is a Result error "camera file '<path>': <field>: <why>".

#include <optional>
#include <string>

#include "telear/core/result.hpp"
#include "telear/vision/camera_model.hpp"

namespace telear::vision {

struct CameraFile {
  CameraModel left;                  // the only camera of a mono file
  std::optional<CameraModel> right;  // set for a stereo file (or a pair of files)
  bool left_has_pose = false;        // the file gave T_cam_base (else the identity)
  bool right_has_pose = false;

  bool is_stereo() const { return right.has_value(); }
};

Result<CameraFile> load_camera_file(const std::string& path);
Result<CameraFile> parse_camera_yaml(const std::string& text, const std::string& source);
// Two mono files, one per eye, as one stereo CameraFile.
Result<CameraFile> load_stereo_camera_files(const std::string& left_path,
                                            const std::string& right_path);

// OpenCV FileStorage YAML text (written by cv::FileStorage, so OpenCV reads it back).
std::string opencv_camera_yaml(const CameraModel& camera);
std::string opencv_stereo_camera_yaml(const StereoCameraModel& cameras);
Status write_camera_file(const CameraModel& camera, const std::string& path);
Status write_stereo_camera_file(const StereoCameraModel& cameras, const std::string& path);

// ROS camera_info YAML (plumb_bob, rectification = I, projection = [K | 0]), plus telear's
// T_cam_base key, which ROS tools ignore.
std::string ros_camera_info_yaml(const CameraModel& camera, const std::string& camera_name);

}  // namespace telear::vision
