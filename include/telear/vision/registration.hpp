#pragma once
// Robot-to-camera registration: the robot base's pose in each camera, T_cam_base, from
// points fixed to the flange seen at several joint configurations (docs/registration.md).
//
// Model. At configuration q_c the flange point p_flange,i lies at
//   p_base,ci = T_base_flange(q_c) * p_flange,i          (forward kinematics, metres)
// and the cameras see it at
//   left:  u_ci = project_L(T_left_base * p_base,ci)
//   right: u_ci = project_R(T_right_left * T_left_base * p_base,ci)
// with the calibrated intrinsics and distortion of camera_model.hpp. T_right_left comes
// from the stereo calibration and is held fixed (the stereo constraint), so the unknown is
// T_left_base alone (6 parameters) and T_right_base = T_right_left * T_left_base.
//
// Solver. (1) Initialisation by cv::solvePnP (SQPnP: >= 3 points, planar or not) on the
// undistorted observations of the eye with more of them (the other eye's pose follows from
// T_right_left). (2) Levenberg-Marquardt over every observation of both eyes jointly:
// residuals r = project(...) - u (2 per observation, pixels), parameters the 6-vector
// delta = (rotation vector, translation) of a left perturbation T_left_base <- exp(delta)
// T_left_base, Jacobian by central differences (2M x 6), normal equations damped by
// lambda * diag(J^T J). Stops when the step is below 1e-10 or after max_iterations.
//
// Degeneracy. A configuration is usable when at least one eye saw its points; it counts as
// distinct when its flange origin is at least min_separation_m from every earlier distinct
// one. Registration needs >= 3 distinct configurations whose observed points are not all on
// one line; the error lists which configurations were set aside and why.
//
// Operator-assisted path: tool_tip_observations() turns hand-clicked tool-tip pixels (one
// per eye and configuration) into the same observations with one point, the tool centre
// point T_flange_tool's origin.

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/core/robot_model.hpp"
#include "telear/vision/camera_model.hpp"
#include "telear/vision/observations_file.hpp"

namespace telear::vision {

struct RegistrationOptions {
  int max_iterations = 100;
  double min_separation_m = 0.01;  // distinct configurations: flange origins this far apart
  int min_configurations = 3;
};

// Reprojection residuals of one eye at the solution.
struct EyeResiduals {
  int observations = 0;  // points used (pixels), not configurations
  double rms_px = 0.0;   // sqrt(mean |r|^2) over those points
  double max_px = 0.0;
};

struct RegistrationResult {
  Eigen::Isometry3d T_left_base = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d T_right_base = Eigen::Isometry3d::Identity();
  EyeResiduals left;
  EyeResiduals right;
  EyeResiduals initial_left;  // after the PnP initialisation, before the joint refinement
  EyeResiduals initial_right;
  int configurations_used = 0;     // distinct configurations
  int iterations = 0;              // Levenberg-Marquardt iterations
  std::vector<std::string> notes;  // configurations set aside and why
};

// The stereo registration described above. `left` and `right` give intrinsics and
// distortion (their T_cam_base is ignored); T_right_left maps left-camera to right-camera
// coordinates (X_R = R X_L + T of the stereo calibration). Errors: q sizes that do not match
// the robot, non-finite values, mismatched pixel counts, fewer than 3 distinct
// configurations, collinear points, points behind a camera.
Result<RegistrationResult> register_stereo(const core::RobotModel& model, const CameraModel& left,
                                           const CameraModel& right,
                                           const Eigen::Isometry3d& T_right_left,
                                           const RegistrationObservations& observations,
                                           const RegistrationOptions& options = {});

// What `telear register` prints after the fit: its notes, the residuals per eye after the PnP
// start and after the refinement (points, RMS, max), and both camera centres in the base frame.
std::string registration_summary(const RegistrationResult& result);

// Reprojection residuals of given poses on the observations (both eyes).
struct StereoResiduals {
  EyeResiduals left;
  EyeResiduals right;
};
StereoResiduals registration_residuals(const core::RobotModel& model, const CameraModel& left,
                                       const CameraModel& right,
                                       const Eigen::Isometry3d& T_left_base,
                                       const Eigen::Isometry3d& T_right_base,
                                       const RegistrationObservations& observations);

// One hand-clicked tool tip: a configuration and the pixel in each eye (nullopt: not
// clicked in that eye).
struct ToolTipClick {
  Eigen::VectorXd q;
  std::optional<Eigen::Vector2d> left;
  std::optional<Eigen::Vector2d> right;
};
RegistrationObservations tool_tip_observations(const core::RobotModel& model,
                                               const std::vector<ToolTipClick>& clicks);

// T_right_left of a stereo pair from its two T_cam_base.
inline Eigen::Isometry3d right_from_left(const Eigen::Isometry3d& T_left_base,
                                         const Eigen::Isometry3d& T_right_base) {
  return T_right_base * T_left_base.inverse();
}

}  // namespace telear::vision
