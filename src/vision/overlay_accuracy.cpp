#include "telear/vision/overlay_accuracy.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "telear/core/angles.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/random_configuration.hpp"

namespace telear::vision {

std::vector<LinkSamples> sample_arm_body(const core::ArmBody& body, double spacing_m) {
  assert(spacing_m > 0.0);
  std::vector<LinkSamples> result;
  const float opening = body.gripper ? body.gripper->opening : 0.0f;
  for (int k = 0; k < body.part_count(); ++k) {
    const core::BodyPart& part = body.parts[static_cast<std::size_t>(k)];
    if (part.mesh.vertices.empty()) continue;
    const Eigen::Isometry3d T_link_part = body.T_link_part(k, opening).cast<double>();
    LinkSamples samples;
    samples.link = part.link;
    auto position = [&part](std::uint32_t index) {
      const float* p = part.mesh.vertices[index].position;
      return Eigen::Vector3d(p[0], p[1], p[2]);
    };
    for (std::uint32_t v = 0; v < part.mesh.vertices.size(); ++v) {
      samples.p_link.push_back(T_link_part * position(v));
    }
    for (std::size_t l = 0; l + 1 < part.mesh.lines.size(); l += 2) {
      const Eigen::Vector3d a = position(part.mesh.lines[l]);
      const Eigen::Vector3d b = position(part.mesh.lines[l + 1]);
      const int steps = static_cast<int>(std::ceil((b - a).norm() / spacing_m));
      for (int s = 1; s < steps; ++s) {
        samples.p_link.push_back(T_link_part * (a + (b - a) * (static_cast<double>(s) / steps)));
      }
    }
    result.push_back(std::move(samples));
  }
  return result;
}

std::vector<Eigen::VectorXd> workspace_configurations(const core::RobotModel& model, int count,
                                                      unsigned seed) {
  std::vector<Eigen::VectorXd> result;
  for (const core::NamedConfiguration& named : model.named_configurations())
    result.push_back(named.q);
  std::mt19937_64 rng(seed);
  for (int c = 0; c < count; ++c) {
    result.push_back(core::random_configuration(model, rng));
  }
  return result;
}

OverlayError overlay_error(const core::RobotModel& model, const std::vector<LinkSamples>& samples,
                           const std::vector<Eigen::VectorXd>& configurations,
                           const CameraModel& truth, const CameraModel& estimate) {
  OverlayError result;
  core::KinematicsData data(model);
  double sum = 0.0;
  for (const Eigen::VectorXd& q : configurations) {
    core::forward_kinematics(model, data, q);
    for (const LinkSamples& part : samples) {
      const Eigen::Isometry3d& T_base_link = data.T_base_link[static_cast<std::size_t>(part.link)];
      for (const Eigen::Vector3d& p_link : part.p_link) {
        const Eigen::Vector3d p_base = T_base_link * p_link;
        const std::optional<Eigen::Vector2d> true_uv = truth.project(p_base);
        if (!true_uv) continue;
        if (true_uv->x() < -0.5 || true_uv->y() < -0.5 || true_uv->x() > truth.width - 0.5 ||
            true_uv->y() > truth.height - 0.5) {
          continue;
        }
        const std::optional<Eigen::Vector2d> estimated_uv = estimate.project(p_base);
        if (!estimated_uv) continue;
        const double error = (*estimated_uv - *true_uv).norm();
        sum += error * error;
        result.max_px = std::max(result.max_px, error);
        ++result.points;
      }
    }
  }
  if (result.points > 0) result.rms_px = std::sqrt(sum / static_cast<double>(result.points));
  return result;
}

PoseError registration_error(const Eigen::Isometry3d& T_cam_base_truth,
                             const Eigen::Isometry3d& T_cam_base_estimate) {
  const Eigen::Isometry3d T_base_cam_truth = T_cam_base_truth.inverse();
  const Eigen::Isometry3d T_base_cam_estimate = T_cam_base_estimate.inverse();
  PoseError error;
  error.position_mm =
      (T_base_cam_estimate.translation() - T_base_cam_truth.translation()).norm() * 1000.0;
  const Eigen::Matrix3d R = T_base_cam_estimate.linear().transpose() * T_base_cam_truth.linear();
  error.rotation_deg = core::degrees_from_radians(Eigen::AngleAxisd(R).angle());
  return error;
}

double stereo_baseline_m(const CameraModel& left, const CameraModel& right) {
  return (right.T_cam_base * left.T_cam_base.inverse()).translation().norm();
}

AccuracyReport evaluate_accuracy(const core::RobotModel& model, const core::ArmBody& body,
                                 const StereoCameraModel& truth, const StereoCameraModel& estimate,
                                 const AccuracyOptions& options) {
  AccuracyReport report;
  const std::vector<LinkSamples> samples = sample_arm_body(body, options.spacing_m);
  const std::vector<Eigen::VectorXd> configurations =
      workspace_configurations(model, options.configurations);
  report.configurations = static_cast<int>(configurations.size());
  for (const LinkSamples& part : samples) {
    report.samples_per_configuration += static_cast<long>(part.p_link.size());
  }
  auto eye = [&](const CameraModel& t, const CameraModel& e) {
    EyeAccuracy accuracy;
    accuracy.truth = t;
    accuracy.estimate = e;
    accuracy.registration = registration_error(t.T_cam_base, e.T_cam_base);
    accuracy.overlay = overlay_error(model, samples, configurations, t, e);
    return accuracy;
  };
  report.left = eye(truth.left, estimate.left);
  report.right = eye(truth.right, estimate.right);
  report.baseline_truth_m = stereo_baseline_m(truth.left, truth.right);
  report.baseline_estimate_m = stereo_baseline_m(estimate.left, estimate.right);
  return report;
}

}  // namespace telear::vision
