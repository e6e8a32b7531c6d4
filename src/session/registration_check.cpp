#include "telear/session/registration_check.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <utility>

#include "telear/core/kinematics.hpp"
#include "telear/vision/marker_detection.hpp"

namespace telear::session {

void corner_residual(const std::vector<Eigen::Vector2d>& detected,
                     const std::vector<Eigen::Vector2d>& predicted, double& rms_px,
                     double& max_px) {
  assert(!detected.empty() && detected.size() == predicted.size());
  double sum2 = 0.0;
  max_px = 0.0;
  for (std::size_t k = 0; k < detected.size(); ++k) {
    const double e = (detected[k] - predicted[k]).norm();
    sum2 += e * e;
    max_px = std::max(max_px, e);
  }
  rms_px = std::sqrt(sum2 / static_cast<double>(detected.size()));
}

RegistrationCheck::RegistrationCheck(core::RobotModelPtr model, vision::StereoCameraModel cameras,
                                     GripperMarker marker)
    : model_(std::move(model)), cameras_(std::move(cameras)), marker_(marker) {
  assert(model_ && "RegistrationCheck: model must not be null");
}

std::vector<Eigen::Vector2d> RegistrationCheck::predict(const vision::CameraModel& camera,
                                                        const Eigen::VectorXd& q) const {
  assert(core::check_joint_vector(*model_, q).ok() && "RegistrationCheck::predict(): invalid q");
  core::KinematicsData data(*model_);
  core::forward_kinematics(*model_, data, q);
  const Eigen::Isometry3d& T_base_flange = data.T_base_link.back();
  std::vector<Eigen::Vector2d> pixels;
  for (const Eigen::Vector3d& p_flange : marker_.corners_flange) {
    const std::optional<Eigen::Vector2d> uv = camera.project(T_base_flange * p_flange);
    if (!uv) return {};
    pixels.push_back(*uv);
  }
  return pixels;
}

EyeResidual RegistrationCheck::check_eye(const cv::Mat& image, const vision::CameraModel& camera,
                                         const Eigen::VectorXd& q) const {
  EyeResidual r;
  r.predicted_px = predict(camera, q);
  r.predicted = !r.predicted_px.empty();
  r.detected_px = vision::detect_aruco_marker(image, marker_.id);
  r.detected = !r.detected_px.empty();
  if (!r.detected) {
    r.message = "marker " + std::to_string(marker_.id) + " not detected in the image";
  } else if (!r.predicted) {
    r.message = "the model puts marker " + std::to_string(marker_.id) + " behind the camera";
  } else {
    corner_residual(r.detected_px, r.predicted_px, r.rms_px, r.max_px);
  }
  return r;
}

StereoResidual RegistrationCheck::check(const cv::Mat& left, const cv::Mat& right,
                                        const Eigen::VectorXd& q) const {
  return {check_eye(left, cameras_.left, q), check_eye(right, cameras_.right, q)};
}

}  // namespace telear::session
