#pragma once
// A pair of ROS camera_info messages -> telear's stereo calibration, as the text of a stereo
// camera file (telear/vision/camera_file.hpp) that the vision server serves through
// GetCameraInfo as if it had been given with --calibration.
//
//   per camera   K, D and distortion_model (plumb_bob, rational_polynomial, equidistant: the
//                three telear's camera model has, each equal to ROS's and OpenCV's) for the
//                raw images; R and P kept as the file's rectification_matrix and
//                projection_matrix; camera_name the header's frame_id
//   the pair     when the two P state a rectified pair (the right one's Tx = -fx' * B), the
//                right camera's pose in the left camera's frame from R1, R2 and P2
//                (telear/vision/rectified_stereo.hpp), as the file's top-level R and T: the
//                only extrinsics camera_info carries. Cameras that are not a rectified pair
//                (P = [K | 0] on both) get no pose between them, and a warning says so.
//
// Refused, with the topic named: a distortion model telear does not have, a D vector of the
// wrong length (or non-zero terms beyond the model's), a malformed K, binning or a region of
// interest (their K is the full sensor's, not the image's), and a camera_info whose size is
// not the images'. An uncalibrated camera (K all zero, as drivers publish before calibration,
// or image_publisher's placeholder fx = fy = 1) is not an error: no calibration, and a warning.

#include <string>
#include <vector>

#include "drivers/ros1/ros1_camera_link.hpp"
#include "telear/core/result.hpp"

namespace telear::drivers::ros1 {

struct CameraInfoCalibration {
  std::string yaml;  // the stereo camera file; empty when a camera is uncalibrated
  std::vector<std::string> warnings;
};

// An image topic and the size of its images.
struct TopicImageSize {
  std::string topic;
  int width = 0, height = 0;
};

Result<CameraInfoCalibration> calibration_from_camera_info(const CameraInfoFields& left,
                                                           const CameraInfoFields& right,
                                                           const TopicImageSize& left_image,
                                                           const TopicImageSize& right_image);

}  // namespace telear::drivers::ros1
