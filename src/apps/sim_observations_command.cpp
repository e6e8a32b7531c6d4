#include "apps/sim_observations_command.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <ostream>
#include <random>

#include "telear/core/angles.hpp"
#include "telear/core/arm_body.hpp"
#include "telear/core/random_configuration.hpp"
#include "telear/core/robot_loader.hpp"
#include "telear/render/egl_context.hpp"
#include "telear/sim/calibration_targets.hpp"
#include "telear/sim/scene_renderer.hpp"
#include "telear/sim/stereo_rig.hpp"
#include "telear/vision/calibration_file.hpp"
#include "telear/vision/marker_detection.hpp"
#include "telear/vision/observations_file.hpp"

namespace telear::cli {
namespace {

constexpr const char* kCommand = "telear sim observations: ";

int fail(std::ostream& err, const std::string& message, int code = 2) {
  err << kCommand << message << "\n";
  return code;
}

// Whether the marker at the scene's current joints faces both cameras and lies well inside
// both images (true cameras, with distortion).
bool marker_well_seen(const sim::SceneRenderer& scene, double min_cos, double margin_px) {
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

// The four corners of marker `id` in an RGB(A) image (cv::aruco order), refined on the black
// border's outer edges (telear/vision/marker_detection.hpp), or empty when it is not found exactly
// once.
std::vector<Eigen::Vector2d> detect_marker(const core::Image& image, int id) {
  const cv::Mat rgb(image.height, image.width, image.channels == 4 ? CV_8UC4 : CV_8UC3,
                    const_cast<std::uint8_t*>(image.pixels.data()));
  return vision::detect_aruco_marker(rgb, id);
}

}  // namespace

int run_sim_observations(const SimObservationsOptions& options, std::ostream& out,
                         std::ostream& err) {
  if (options.configs < 1 || options.configs > 500)
    return fail(err, "--configs " + std::to_string(options.configs) + " is outside 1..500");
  if (options.output.empty())
    return fail(err, "-o: give the observations file to write, e.g. -o obs.yaml");
  if (Status s = vision::check_output_path(options.output, "-o"); !s)
    return fail(err, s.error().message);
  if (!(options.noise >= 0.0 && options.noise <= 50.0))
    return fail(err, "--noise must be within 0..50 grey levels");
  if (options.supersample < 1 || options.supersample > 8)
    return fail(err, "--supersample must be within 1..8");

  auto rig = sim::load_stereo_rig(options.rig);
  if (!rig) return fail(err, "--rig: " + rig.error().message);
  auto model = core::load_robot(options.robot);
  if (!model) return fail(err, "--robot: " + model.error().message);
  auto body = rig->body_file.empty() ? core::body_description_for(**model)
                                     : load_body_yaml_file(rig->body_file, **model);
  if (!body) return fail(err, "--rig: " + body.error().message);

  auto context = render::create_headless_context();
  if (!context) return fail(err, context.error().message, 1);
  sim::SceneOptions scene_options;
  scene_options.seed = options.seed;
  scene_options.noise_sigma = options.noise;
  scene_options.supersample = options.supersample;
  auto scene = sim::SceneRenderer::create(*rig, **model, *body, scene_options);
  if (!scene) return fail(err, scene.error().message, 1);
  if (!scene->marker()) return fail(err, "the scene has no marker on the gripper", 1);
  const sim::ArucoMarker& marker = *scene->marker();

  const core::RobotModel& robot = **model;
  std::mt19937_64 rng(options.seed);

  vision::RegistrationObservations observations;
  observations.robot = options.robot;
  observations.point_in_flange.assign(marker.corners_flange.begin(), marker.corners_flange.end());
  const double min_cos = std::cos(core::radians_from_degrees(options.max_view_angle_deg));
  const long max_draws = 20000L * options.configs;
  long draws = 0;
  int skipped = 0;
  for (int c = 0; c < options.configs; ++c) {
    Eigen::VectorXd q;
    do {
      if (++draws > max_draws) {
        return fail(err,
                    "found only " + std::to_string(c) + " of " + std::to_string(options.configs) +
                        " configurations at which the marker faces both cameras; check the "
                        "rig's pose",
                    2);
      }
      q = core::random_configuration(robot, rng);
      scene->set_configuration(q);
    } while (!marker_well_seen(*scene, min_cos, options.margin_px));

    vision::ObservedConfiguration observed;
    observed.q = q;
    const auto frame = static_cast<std::uint64_t>(c);
    observed.left_pixels = detect_marker(scene->render(sim::Eye::kLeft, frame), marker.mount.id);
    observed.right_pixels = detect_marker(scene->render(sim::Eye::kRight, frame), marker.mount.id);
    out << "configuration " << (c + 1) << "/" << options.configs << ": left "
        << (observed.left_pixels.empty() ? "not found" : "found") << ", right "
        << (observed.right_pixels.empty() ? "not found" : "found");
    if (observed.left_pixels.empty() && observed.right_pixels.empty()) {
      ++skipped;
      out << " (skipped: the marker was not detected in either image)\n" << std::flush;
      continue;
    }
    out << "\n" << std::flush;
    observations.configurations.push_back(std::move(observed));
  }
  if (observations.configurations.empty()) {
    return fail(err,
                "the marker was not detected at any of the " + std::to_string(options.configs) +
                    " configurations",
                1);
  }
  if (Status s = vision::write_observations_file(observations, options.output); !s) {
    return fail(err, s.error().message, 1);
  }
  out << "wrote " << observations.configurations.size() << " configurations to " << options.output;
  if (skipped > 0) out << " (" << skipped << " skipped: marker not detected)";
  out << "\n";
  return 0;
}

}  // namespace telear::cli
