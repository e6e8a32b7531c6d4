#pragma once
// Camera files (docs/cameras.md). Three layouts are read, by one parser:
//
// OpenCV FileStorage YAML, what cv::FileStorage writes and telear writes:
//   %YAML:1.0
//   ---
//   image_width: 640
//   image_height: 480
//   camera_matrix: !!opencv-matrix             # 3x3, pixels; [0][1] = skew = alpha_c * fx
//     {rows: 3, cols: 3, dt: d, data: [fx, s, cx, 0, fy, cy, 0, 0, 1]}
//   distortion_model: plumb_bob                # or rational_polynomial, equidistant
//   distortion_coefficients: !!opencv-matrix   # the model's D: 5, 8 or 4 values
//     {rows: 1, cols: 5, dt: d, data: [...]}
//   T_cam_base: !!opencv-matrix                # 4x4 row-major, metres: p_cam = T p_base
//     {rows: 4, cols: 4, dt: d, data: [...]}
//
// OpenCV FileStorage XML (<opencv_storage>) with the same keys: converted to the YAML above by
// cv::FileStorage (opencv_storage.hpp) and parsed by the same code, so the checks and messages
// are the same. A file is XML when its text starts with '<'.
//
// ROS camera_info YAML (camera_calibration_parsers): image_width, image_height, camera_name,
// camera_matrix {rows, cols, data}, distortion_model (plumb_bob, rational_polynomial or
// equidistant), distortion_coefficients, rectification_matrix (R, a rotation) and
// projection_matrix (P, 3x4, last row 0 0 1 0). K and D describe the raw image, which is what
// telear renders through; R and P are checked and kept (CameraFile::left_rectification), and
// a pair of such files gives the stereo geometry (rectified_stereo.hpp).
//
// A stereo file holds the per-camera keys in a `left:` and a `right:` map; a stereo pair can
// also come as two mono files ("left.yaml,right.yaml" wherever a camera file is accepted).
// T_cam_base is optional in every layout (a camera calibrated but not yet registered to the
// robot): without it the pose is the identity and has_pose is false. distortion_model is
// optional (plumb_bob); a plumb_bob D may have 4, 5, 8, 12 or 14 values (OpenCV's lengths)
// when those beyond k3 are zero, a rational_polynomial D 8, 12 or 14 (beyond k6 zero), an
// equidistant D exactly 4.
//
// Every malformed input is a Result error "camera file '<path>': <field>: <why>" (a pair's
// own checks: "stereo pair '<left>', '<right>': ...").

#include <optional>
#include <string>

#include "telear/core/result.hpp"
#include "telear/vision/camera_model.hpp"
#include "telear/vision/opencv_storage.hpp"
#include "telear/vision/rectified_stereo.hpp"

namespace telear::vision {

struct CameraFile {
  CameraModel left;                  // the only camera of a mono file
  std::optional<CameraModel> right;  // set for a stereo file (or a pair of files)
  bool left_has_pose = false;        // the file gave T_cam_base (else the identity)
  bool right_has_pose = false;
  // A ROS camera_info file's rectification_matrix and projection_matrix, and camera_name.
  std::optional<Rectification> left_rectification;
  std::optional<Rectification> right_rectification;
  std::string left_name;
  std::string right_name;
  // The right camera's pose in the left camera's frame (p_right = T p_left), when the input
  // states it: a ROS stereo pair (from R1, R2 and P2) or a stereo calibration file's R and T.
  // A ROS pair, calibrated but not registered, also gets left.T_cam_base = I and
  // right.T_cam_base = T_right_left (stereo_calibration.hpp's convention), has_pose false.
  std::optional<Eigen::Isometry3d> T_right_left;

  bool is_stereo() const { return right.has_value(); }
};

// A file in any of the layouts above. `path` may also name a pair, "left.yaml,right.yaml"
// (when no file has that name), read by load_stereo_camera_files().
Result<CameraFile> load_camera_file(const std::string& path);
// The text of a camera file (YAML, or XML when it starts with '<'); `source` names it in
// messages.
Result<CameraFile> parse_camera_yaml(const std::string& text, const std::string& source);
// Two mono files, one per eye, as one stereo CameraFile. When both are ROS camera_info files
// without T_cam_base, they are read as a rectified pair by load_ros_stereo_pair().
Result<CameraFile> load_stereo_camera_files(const std::string& left_path,
                                            const std::string& right_path);
// Two ROS camera_info files of one rectified pair (camera_calibration's left.yaml and
// right.yaml, or ros_stereo_camera_info_yaml()'s): the cameras with T_right_left recovered
// from R1, R2 and P2 (rectified_stereo.hpp). Errors: either file not a mono ROS camera_info
// file, the two disagreeing in image size or distortion_model, and right_from_left_rectified's
// (no baseline: the right P's Tx = 0).
Result<CameraFile> load_ros_stereo_pair(const std::string& left_path,
                                        const std::string& right_path);

// OpenCV FileStorage text (written by cv::FileStorage, so OpenCV reads it back), YAML or XML.
// Every camera has distortion_model and the model's D vector (5, 8 or 4 values).
std::string opencv_camera_yaml(const CameraModel& camera);
std::string opencv_stereo_camera_yaml(const StereoCameraModel& cameras);
std::string opencv_camera_text(const CameraModel& camera, OpenCvStorageFormat format);
std::string opencv_stereo_camera_text(const StereoCameraModel& cameras, OpenCvStorageFormat format);
// XML when `path` ends in ".xml", else YAML.
Status write_camera_file(const CameraModel& camera, const std::string& path);
Status write_stereo_camera_file(const StereoCameraModel& cameras, const std::string& path);

// ROS camera_info YAML (the camera's distortion_model and D, rectification = I, projection =
// [K | 0]), plus telear's T_cam_base key, which ROS tools ignore.
std::string ros_camera_info_yaml(const CameraModel& camera, const std::string& camera_name);

}  // namespace telear::vision
