#pragma once
// Calibration output files: OpenCV FileStorage YAML with the camera keys of docs/cameras.md
// (image_width, image_height, camera_matrix, distortion_model, distortion_coefficients with
// the model's 5, 8 or 4 values), per camera in `left`
// and `right` maps for a stereo pair, and *without* T_cam_base: the cameras are calibrated
// but not registered to the robot yet (`telear register` adds the poses; until then
// load_camera_file() reads has_pose = false and `telear render` asks for registration).
// A stereo calibration adds the pair's geometry at the top level, which camera-file readers
// ignore and OpenCV programs read with cv::FileStorage:
//
//   R: 3x3, T: 3x1        left camera -> right camera, X_R = R X_L + T (pattern units, m)
//   E: 3x3, F: 3x3        essential and fundamental matrices
//   R1, R2: 3x3           rectifying rotations (cv::stereoRectify)
//   P1, P2: 3x4, Q: 4x4   rectified projections and disparity-to-depth matrix
//   rms_px                the calibration's reprojection RMS, pixels
//   calibration_pattern   the pattern spec used, e.g. "chessboard:9x6:0.025"
//
// A target path ending in ".xml" gets the same keys as OpenCV FileStorage XML
// (write_files_atomically converts; see text_for_path).
//
// Files are replaced atomically: every text goes first to a temporary file in its target's
// directory, and only when all were written are they renamed over their targets; on
// failure the temporaries are removed and no target is created or changed.

#include <string>
#include <utility>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/vision/mono_calibration.hpp"
#include "telear/vision/stereo_calibration.hpp"

namespace telear::vision {

std::string mono_calibration_yaml(const MonoCalibration& calibration,
                                  const CalibrationPattern& pattern);
std::string stereo_calibration_yaml(const StereoCalibration& calibration,
                                    const CalibrationPattern& pattern);

// ROS camera_info YAML (camera_calibration_parsers' layout, the camera's distortion_model and
// its D vector), without telear's
// T_cam_base key. Mono: rectification I, projection [K | 0]. Stereo, one camera (`right`
// selects it): rectification_matrix R1 or R2 and projection_matrix P1 or P2.
std::string ros_mono_camera_info_yaml(const MonoCalibration& calibration,
                                      const std::string& camera_name);
std::string ros_stereo_camera_info_yaml(const StereoCalibration& calibration, bool right,
                                        const std::string& camera_name);

// R, T of a stereo calibration file (X_R = R X_L + T), for registration, in YAML or XML; or of
// a pair of ROS camera_info files given as "left.yaml,right.yaml" (load_ros_stereo_pair).
// Errors name the file and say what is missing or wrong.
struct StereoGeometry {
  cv::Matx33d R;
  cv::Vec3d T;
};
Result<StereoGeometry> load_stereo_geometry(const std::string& path);

// Fails early, before a long computation, when `path` cannot be created: its directory is
// missing or not writable, or `path` is a directory. `option` names the CLI option.
Status check_output_path(const std::string& path, const std::string& option);

// `text` as it goes to `path`: OpenCV FileStorage YAML (text starting with "%YAML") bound for
// a path ending in ".xml" is converted to FileStorage XML with the same keys; anything else is
// returned unchanged.
Result<std::string> text_for_path(const std::string& text, const std::string& path);

// (path, text) pairs written all-or-nothing as described above, through text_for_path().
Status write_files_atomically(const std::vector<std::pair<std::string, std::string>>& files);

}  // namespace telear::vision
