#include "telear/sim/marker_observations.hpp"

#include "telear/sim/rig_robot.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <random>

#include "telear/core/angles.hpp"
#include "telear/core/arm_body.hpp"
#include "telear/core/random_configuration.hpp"
#include "telear/core/robot_loader.hpp"
#include "telear/geometry/collision_checker.hpp"
#include "telear/render/egl_context.hpp"
#include "telear/sim/calibration_targets.hpp"
#include "telear/sim/scene_renderer.hpp"
#include "telear/sim/stereo_rig.hpp"
#include "telear/vision/marker_detection.hpp"

namespace telear::sim {
namespace {

// Whether the marker at the scene's current joints faces both cameras and lies well inside
// both images (true cameras, with distortion).
bool marker_well_seen(const SceneRenderer& scene, double min_cos, double margin_px) {
  const Eigen::Isometry3d T_base_marker =
      scene.T_base_flange() * scene.marker()->mount.T_flange_marker;
  const Eigen::Vector3d normal = T_base_marker.linear().col(2);
  const Eigen::Vector3d centre = T_base_marker.translation();
  const std::array<Eigen::Vector3d, 4> corners = scene.marker_corners_base();
  for (const vision::CameraModel* camera :
       {&scene.rig().cameras.left, &scene.rig().cameras.right}) {
    const Eigen::Vector3d optical_centre = camera->T_cam_base.inverse().translation();
    if (normal.dot((optical_centre - centre).normalized()) < min_cos) return false;
    for (const Eigen::Vector3d& corner : corners) {
      const std::optional<Eigen::Vector2d> uv = camera->project(corner);
      if (!uv || (*uv).x() < margin_px || (*uv).y() < margin_px ||
          (*uv).x() > camera->width - 1 - margin_px || (*uv).y() > camera->height - 1 - margin_px)
        return false;
    }
  }
  return true;
}

// The four corners of marker `id` in an RGB(A) image (cv::aruco order), or empty when it is
// not found exactly once.
std::vector<Eigen::Vector2d> detect_marker(const core::Image& image, int id) {
  const cv::Mat rgb(image.height, image.width, image.channels == 4 ? CV_8UC4 : CV_8UC3,
                    const_cast<std::uint8_t*>(image.pixels.data()));
  return vision::detect_aruco_marker(rgb, id);
}

}  // namespace

Status MarkerObservationsOptions::validate() const {
  if (configurations < 1 || configurations > 500) {
    return Error{"configurations " + std::to_string(configurations) + " is outside 1..500"};
  }
  if (!(noise_grey >= 0.0 && noise_grey <= 50.0)) {
    return Error{"noise_grey must be within 0..50 grey levels"};
  }
  if (supersample < 1 || supersample > 8) return Error{"supersample must be within 1..8"};
  if (!(max_view_angle_deg > 0.0 && max_view_angle_deg < 90.0)) {
    return Error{"max_view_angle_deg must be within 0..90 deg (exclusive)"};
  }
  if (!(margin_px >= 0.0)) return Error{"margin_px must be at least 0"};
  return Status::Ok();
}

Result<MarkerObservations> simulate_marker_observations(const MarkerObservationsOptions& options,
                                                        const ObservationProgress& progress) {
  if (Status s = options.validate(); !s) return s.error();
  auto rig = load_stereo_rig(options.rig_file);
  if (!rig) return Error{"rig_file: " + rig.error().message};
  auto loaded = load_rig_robot(*rig, {options.robot, options.tip, options.geometry.package_paths},
                               options.geometry);
  if (!loaded) return Error{"robot: " + loaded.error().message};
  const core::RobotModelPtr model = loaded->model();
  const core::BodyDescription* body = &loaded->body;

  auto context = render::create_headless_context();
  if (!context) return context.error();
  SceneOptions scene_options;
  scene_options.seed = options.seed;
  scene_options.noise_sigma = options.noise_grey;
  scene_options.supersample = options.supersample;
  scene_options.marker = loaded->description.marker;
  auto scene = SceneRenderer::create(*rig, *model, *body, scene_options);
  if (!scene) return scene.error();
  if (!scene->marker()) return Error{"the scene has no marker on the gripper"};
  const ArucoMarker& marker = *scene->marker();

  // collision_free: only configurations the robot server would accept. One in contact with the
  // arm itself or the rig's scene is refused as a start or a pose (the demo's capture starts at
  // one), and the random draw over a UR-type arm's +-360 deg joints hits them often.
  std::optional<geometry::CollisionChecker> checker;
  if (options.collision_free) {
    geometry::CollisionSetupOptions setup;
    setup.geometry = options.geometry;
    auto made = geometry::make_collision_checker(loaded->description, rig->workspace, setup);
    if (!made) return Error{"collision checker: " + made.error().message};
    checker.emplace(std::move(made).value());
  }

  const core::RobotModel& robot = *model;
  std::mt19937_64 rng(options.seed);

  MarkerObservations result;
  vision::RegistrationObservations& observations = result.observations;
  observations.robot = options.robot;
  observations.point_in_flange.assign(marker.corners_flange.begin(), marker.corners_flange.end());
  const double min_cos = std::cos(core::radians_from_degrees(options.max_view_angle_deg));
  const long max_draws = 20000L * options.configurations;
  long draws = 0;
  for (int c = 0; c < options.configurations; ++c) {
    Eigen::VectorXd q;
    do {
      if (++draws > max_draws) {
        return Error{"found only " + std::to_string(c) + " of " +
                     std::to_string(options.configurations) +
                     std::string(checker ? " collision-free" : "") +
                     " configurations at which the marker faces both cameras; "
                     "check the rig's pose"};
      }
      q = core::random_configuration(robot, rng);
      scene->set_configuration(q);
    } while (!marker_well_seen(*scene, min_cos, options.margin_px) ||
             (checker && !checker->check(q).collision_free()));

    vision::ObservedConfiguration observed;
    observed.q = q;
    const auto frame = static_cast<std::uint64_t>(c);
    observed.left_pixels = detect_marker(scene->render(Eye::kLeft, frame), marker.mount.id);
    observed.right_pixels = detect_marker(scene->render(Eye::kRight, frame), marker.mount.id);
    const bool left_found = !observed.left_pixels.empty();
    const bool right_found = !observed.right_pixels.empty();
    if (progress) progress(c + 1, options.configurations, left_found, right_found);
    if (!left_found && !right_found) {
      ++result.skipped;
      continue;
    }
    observations.configurations.push_back(std::move(observed));
  }
  if (observations.configurations.empty()) {
    return Error{"the marker was not detected at any of the " +
                 std::to_string(options.configurations) + " configurations"};
  }
  return result;
}

}  // namespace telear::sim
