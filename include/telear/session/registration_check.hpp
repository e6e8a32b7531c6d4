#pragma once
// The live registration check: how far the gripper's ArUco marker, as detected in each eye's
// image, lies from where the model puts it -- forward kinematics of the reported joints, the
// marker's corners fixed in the flange frame, and the calibrated camera (intrinsics,
// distortion, T_cam_base from registration):
//
//   p_base_k = T_base_flange(q) * p_flange_k                       k = 0..3 (cv::aruco order)
//   predicted_k = camera.project(p_base_k)                          (pixels, with distortion)
//   detected_k  = detect_aruco_marker(image, id)                    (vision/marker_detection)
//   rms = sqrt( (1/4) sum_k |detected_k - predicted_k|^2 ),  max = max_k |...|   (pixels)
//
// This is the overlay error the operator sees (the ghost drawn at the real robot's q lands
// rms pixels off the arm in the video), so the session shows it per eye, continuously, and a
// growing value says the calibration or registration no longer holds (a bumped camera).
// q must be the joints at the image's capture time (the frame's scene state, or the robot
// state nearest to it), otherwise arm motion adds to the residual.
//
// A plain value class: check() is const and allocates its own FK workspace, so it may run on
// any thread.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "telear/core/robot_model.hpp"
#include "telear/vision/camera_model.hpp"

namespace telear::session {

struct GripperMarker {
  int id = 0;                                     // DICT_4X4_50 id
  std::array<Eigen::Vector3d, 4> corners_flange;  // m, flange frame, cv::aruco corner order
};

struct EyeResidual {
  bool detected = false;   // the marker was found (exactly once) in the image
  bool predicted = false;  // all four corners project in front of the camera
  std::vector<Eigen::Vector2d> detected_px, predicted_px;  // 4 each when set
  double rms_px = 0.0;                                     // valid when detected && predicted
  double max_px = 0.0;
  std::string message;  // why there is no residual, or "" when there is one
  bool valid() const { return detected && predicted; }
};

struct StereoResidual {
  EyeResidual left, right;
  // The robot's reported joints changed within +-kMotionWindowS of the frame's capture (by
  // more than kMotionToleranceRad): a moving arm's residual adds any mismatch between the
  // frame's time and the state it is drawn with, an arm at rest's does not (Session fills it).
  bool arm_moving = false;
  static constexpr double kMotionWindowS = 0.1;
  static constexpr double kMotionToleranceRad = 1e-4;
};

class RegistrationCheck {
 public:
  // `model` must not be null; the cameras' T_cam_base place them in the robot's base frame.
  RegistrationCheck(core::RobotModelPtr model, vision::StereoCameraModel cameras,
                    GripperMarker marker);

  const vision::StereoCameraModel& cameras() const { return cameras_; }
  const GripperMarker& marker() const { return marker_; }

  // Where the model puts the marker's corners in `camera` at q (empty when a corner is at or
  // behind the camera). q must have dof() finite values (asserted: the session validates the
  // robot's state first).
  std::vector<Eigen::Vector2d> predict(const vision::CameraModel& camera,
                                       const Eigen::VectorXd& q) const;

  // One eye: `image` 8-bit grey, RGB or RGBA at the camera's size.
  EyeResidual check_eye(const cv::Mat& image, const vision::CameraModel& camera,
                        const Eigen::VectorXd& q) const;
  StereoResidual check(const cv::Mat& left, const cv::Mat& right, const Eigen::VectorXd& q) const;

 private:
  core::RobotModelPtr model_;
  vision::StereoCameraModel cameras_;
  GripperMarker marker_;
};

// RMS and max of |detected_k - predicted_k| over corresponding points (same size, > 0).
void corner_residual(const std::vector<Eigen::Vector2d>& detected,
                     const std::vector<Eigen::Vector2d>& predicted, double& rms_px, double& max_px);

}  // namespace telear::session
