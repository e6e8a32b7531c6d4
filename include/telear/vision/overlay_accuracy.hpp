#pragma once
// Accuracy of a calibration + registration against ground truth (docs/registration.md).
//
// Overlay error: where the ghost is drawn versus where the real arm is. Points are sampled
// densely on every part of the arm's body (telear/core/arm_body.hpp: each part's mesh vertices and
// points every `spacing_m` along its wire-frame edges, in the part's link frame). At each
// configuration q of a set covering the workspace, every point goes to the base frame by the
// true robot's forward kinematics, p_base = T_base_link[link](q) * T_link_part * p_part, and
// is projected twice: with the true camera (intrinsics, distortion, T_cam_base) and with the
// estimated one. The error of a point is the distance between the two pixels; points whose
// true pixel is outside the image or that are behind either camera are not counted. Reported
// per eye: RMS and maximum over all counted points of all configurations.
//
// Registration error of an eye: the camera's pose in the base frame, T_base_cam =
// T_cam_base^-1; position error |c_est - c_true| (mm) of the optical centre, and rotation
// error = the angle of R_est^T R_true (degrees). Baseline: |t| of T_right_left =
// T_right_base T_left_base^-1 (m).

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "telear/core/arm_body.hpp"
#include "telear/core/robot_model.hpp"
#include "telear/vision/camera_model.hpp"

namespace telear::vision {

// Points on one body part, in the frame of the link the part moves with.
struct LinkSamples {
  int link = 0;
  std::vector<Eigen::Vector3d> p_link;
};

// Mesh vertices and points every spacing_m (> 0) along every wire-frame edge of every part.
std::vector<LinkSamples> sample_arm_body(const core::ArmBody& body, double spacing_m = 0.01);

// `count` configurations uniformly within the joint limits (infinite limits: [-pi, pi]) from a
// fixed seed, preceded by the model's named configurations: reproducible workspace coverage.
std::vector<Eigen::VectorXd> workspace_configurations(const core::RobotModel& model, int count,
                                                      unsigned seed = 20240601u);

struct OverlayError {
  long points = 0;  // (point, configuration) pairs counted
  double rms_px = 0.0;
  double max_px = 0.0;
};

OverlayError overlay_error(const core::RobotModel& model, const std::vector<LinkSamples>& samples,
                           const std::vector<Eigen::VectorXd>& configurations,
                           const CameraModel& truth, const CameraModel& estimate);

struct PoseError {
  double position_mm = 0.0;
  double rotation_deg = 0.0;
};
// Error of an estimated T_cam_base against the true one (camera pose in the base frame).
PoseError registration_error(const Eigen::Isometry3d& T_cam_base_truth,
                             const Eigen::Isometry3d& T_cam_base_estimate);

double stereo_baseline_m(const CameraModel& left, const CameraModel& right);

// The whole accuracy table for a stereo pair.
struct EyeAccuracy {
  CameraModel truth;
  CameraModel estimate;
  PoseError registration;
  OverlayError overlay;
};
struct AccuracyReport {
  EyeAccuracy left;
  EyeAccuracy right;
  double baseline_truth_m = 0.0;
  double baseline_estimate_m = 0.0;
  int configurations = 0;  // of the overlay
  long samples_per_configuration = 0;
};

struct AccuracyOptions {
  int configurations = 60;  // random ones, beside the named configurations
  double spacing_m = 0.01;  // sample spacing along the body's edges
};

AccuracyReport evaluate_accuracy(const core::RobotModel& model, const core::ArmBody& body,
                                 const StereoCameraModel& truth, const StereoCameraModel& estimate,
                                 const AccuracyOptions& options = {});

}  // namespace telear::vision
