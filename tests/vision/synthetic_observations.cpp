#include "synthetic_observations.hpp"

#include <gtest/gtest.h>

#include <optional>
#include <random>

#include "telear/core/kinematics.hpp"
#include "telear/core/random_configuration.hpp"
#include "telear/vision/camera_file.hpp"
#include "telear/vision/registration.hpp"
#include "test_util/test_util.hpp"

namespace telear::test {
namespace {

bool inside(const vision::CameraModel& camera, const std::optional<Eigen::Vector2d>& uv) {
  return uv && uv->x() > 10 && uv->y() > 10 && uv->x() < camera.width - 10 &&
         uv->y() < camera.height - 10;
}

}  // namespace

Eigen::Isometry3d T_right_left_of(const vision::StereoCameraModel& rig) {
  return vision::right_from_left(rig.left.T_cam_base, rig.right.T_cam_base);
}

vision::CalibrationPattern chessboard_9x6() {
  return *vision::parse_calibration_pattern("chessboard:9x6:0.03");
}

vision::StereoCameraModel shipped_stereo_cameras() {
  Result<vision::CameraFile> file =
      vision::load_camera_file(data_path("cameras/puma560_stereo.yaml"));
  EXPECT_TRUE(file.ok()) << (file.ok() ? "" : file.error().message);
  return {file->left, *file->right};
}

std::vector<Eigen::Vector3d> flange_marker_corners() {
  return {
      {-0.025, -0.025, 0.05}, {0.025, -0.025, 0.05}, {0.025, 0.025, 0.05}, {-0.025, 0.025, 0.05}};
}

vision::RegistrationObservations synthetic_observations(const core::RobotModel& model,
                                                        const vision::StereoCameraModel& rig,
                                                        const std::vector<Eigen::Vector3d>& points,
                                                        int count, double noise_px, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, noise_px);
  vision::RegistrationObservations observations;
  observations.robot = model.name();
  observations.point_in_flange = points;
  core::KinematicsData data(model);
  while (static_cast<int>(observations.configurations.size()) < count) {
    vision::ObservedConfiguration configuration;
    configuration.q = core::random_configuration(model, rng);
    core::forward_kinematics(model, data, configuration.q);
    bool visible = true;
    for (const Eigen::Vector3d& p : points) {
      const Eigen::Vector3d p_base = data.T_base_link.back() * p;
      const auto l = rig.left.project(p_base);
      const auto r = rig.right.project(p_base);
      if (!inside(rig.left, l) || !inside(rig.right, r)) {
        visible = false;
        break;
      }
      configuration.left_pixels.push_back(*l + Eigen::Vector2d(noise(rng), noise(rng)));
      configuration.right_pixels.push_back(*r + Eigen::Vector2d(noise(rng), noise(rng)));
    }
    if (visible) observations.configurations.push_back(configuration);
  }
  return observations;
}

}  // namespace telear::test
