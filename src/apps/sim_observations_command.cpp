#include "apps/sim_observations_command.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <opencv2/aruco.hpp>
#include <opencv2/imgproc.hpp>
#include <ostream>
#include <random>

#include "core/angles.hpp"
#include "core/arm_body.hpp"
#include "core/random_configuration.hpp"
#include "core/robot_loader.hpp"
#include "render/egl_context.hpp"
#include "sim/calibration_targets.hpp"
#include "sim/scene_renderer.hpp"
#include "sim/stereo_rig.hpp"
#include "vision/calibration_file.hpp"
#include "vision/observations_file.hpp"

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
      scene.T_base_flange() * scene.marker()->spec.T_flange_marker;
  const Eigen::Vector3d normal = T_base_marker.linear().col(2);
  const Eigen::Vector3d centre = T_base_marker.translation();
  const std::array<Eigen::Vector3d, 4> corners = scene.marker_corners_base();
  for (const CameraModel* camera : {&scene.rig().cameras.left, &scene.rig().cameras.right}) {
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

// Bilinear sample of a CV_8UC1 image at (x, y) (pixel centres at integers); the caller keeps
// the point at least one pixel inside the image.
double sample(const cv::Mat& grey, const Eigen::Vector2d& p) {
  const int x0 = static_cast<int>(std::floor(p.x()));
  const int y0 = static_cast<int>(std::floor(p.y()));
  const double fx = p.x() - x0, fy = p.y() - y0;
  const auto at = [&grey](int x, int y) {
    return static_cast<double>(grey.at<std::uint8_t>(y, x));
  };
  return (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) +
         fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1));
}

double median(std::vector<double> values) {
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

// Refines the detector's quad. On a marker of ~20 px (cells of ~3 px) cv::aruco's corners are
// only whole-pixel accurate: its contour corners lie on integer pixels, and cornerSubPix's
// window reaches the inner bit corners, so it either drifts onto them (errors of several px)
// or gives up and keeps the integer point. Instead, each side's OUTER edge of the black border
// (black inside, the white quiet zone outside) is located to sub-pixel precision where the
// grey profile along the side's normal crosses the midpoint between the two levels (the
// anti-aliased edge is a symmetric blur of a step, so the half-level crossing is the edge),
// at points along the middle 70 % of the side (away from the corners, where two edges mix);
// a line is fitted to them by total least squares, and neighbouring lines are intersected.
// The search along the normal stays within half a cell of the current edge, so the inner
// bit edges (one cell further in) and the quiet zone's outer edge do not interfere.
// Returns the corners unchanged when the edges cannot be measured (low contrast, too small,
// near the image border, or a corner that would move more than 2 px).
std::vector<Eigen::Vector2d> refine_corners_by_edges(const cv::Mat& grey,
                                                     const std::vector<Eigen::Vector2d>& initial) {
  constexpr int kCells = 6;  // DICT_4X4: 4 x 4 bits inside a one-cell black border
  std::vector<Eigen::Vector2d> corners = initial;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (const auto& c : initial) centre += c / 4.0;
  for (int iteration = 0; iteration < 3; ++iteration) {
    std::array<Eigen::Vector3d, 4> lines;  // a x + b y + c = 0, (a, b) unit
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector2d a = corners[k], b = corners[(k + 1) % 4];
      const double length = (b - a).norm();
      if (length < 8.0) return initial;
      const double cell = length / kCells;
      const Eigen::Vector2d along = (b - a) / length;
      Eigen::Vector2d normal(-along.y(), along.x());
      if (normal.dot(0.5 * (a + b) - centre) < 0) normal = -normal;  // outwards
      const double reach = 0.5 * cell;
      const int samples = std::max(8, static_cast<int>(2 * length));
      std::vector<Eigen::Vector2d> bases;
      for (int i = 0; i < samples; ++i) {
        bases.push_back(a + (b - a) * (0.15 + 0.7 * (i + 0.5) / samples));
      }
      for (const Eigen::Vector2d& p : bases) {
        for (const double s : {-reach - 1.0, reach + 1.0}) {
          const Eigen::Vector2d q = p + s * normal;
          if (q.x() < 1 || q.y() < 1 || q.x() > grey.cols - 2 || q.y() > grey.rows - 2)
            return initial;
        }
      }
      std::vector<double> dark, light;
      for (const Eigen::Vector2d& p : bases) {
        dark.push_back(sample(grey, p - reach * normal));
        light.push_back(sample(grey, p + reach * normal));
      }
      const double black = median(dark), white = median(light);
      if (white - black < 20.0) return initial;
      const double level = 0.5 * (black + white);
      std::vector<Eigen::Vector2d> edge;
      constexpr double kStep = 0.05;
      for (const Eigen::Vector2d& p : bases) {
        // The half-level crossing (dark -> light going outwards) nearest to the current line.
        double best = std::numeric_limits<double>::infinity();
        double previous = sample(grey, p - reach * normal);
        for (double s = -reach; s < reach; s += kStep) {
          const double next = sample(grey, p + (s + kStep) * normal);
          if (previous < level && next >= level) {
            const double crossing = s + kStep * (level - previous) / (next - previous);
            if (std::abs(crossing) < std::abs(best)) best = crossing;
          }
          previous = next;
        }
        if (std::isfinite(best)) edge.push_back(p + best * normal);
      }
      if (edge.size() < 5) return initial;
      Eigen::Vector2d mean = Eigen::Vector2d::Zero();
      for (const auto& e : edge) mean += e / static_cast<double>(edge.size());
      Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
      for (const auto& e : edge) scatter += (e - mean) * (e - mean).transpose();
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(scatter);
      const Eigen::Vector2d line_normal = solver.eigenvectors().col(0);  // smallest eigenvalue
      lines[k] = Eigen::Vector3d(line_normal.x(), line_normal.y(), -line_normal.dot(mean));
    }
    for (int k = 0; k < 4; ++k) {
      // Corner k joins side k - 1 (from corner k - 1) and side k (to corner k + 1).
      const Eigen::Vector3d point = lines[(k + 3) % 4].cross(lines[k]);
      if (std::abs(point.z()) < 1e-6) return initial;
      corners[k] = point.head<2>() / point.z();
      if ((corners[k] - initial[k]).norm() > 4.0) return initial;
    }
  }
  return corners;
}

// The four corners of marker `id` in an RGB image (cv::aruco order), or empty when it is not
// found exactly once. The detector's corners are refined on the black border's outer edges
// (refine_corners_by_edges).
std::vector<Eigen::Vector2d> detect_marker(const render::Image& image, int id) {
  const cv::Mat rgb(image.height, image.width, image.channels == 4 ? CV_8UC4 : CV_8UC3,
                    const_cast<std::uint8_t*>(image.pixels.data()));
  cv::Mat grey;
  cv::cvtColor(rgb, grey, image.channels == 4 ? cv::COLOR_RGBA2GRAY : cv::COLOR_RGB2GRAY);
  const cv::Ptr<cv::aruco::Dictionary> dictionary =
      cv::aruco::getPredefinedDictionary(cv::aruco::DICT_4X4_50);
  cv::Ptr<cv::aruco::DetectorParameters> parameters = cv::aruco::DetectorParameters::create();
  parameters->cornerRefinementMethod = cv::aruco::CORNER_REFINE_NONE;
  std::vector<std::vector<cv::Point2f>> corners;
  std::vector<int> ids;
  cv::aruco::detectMarkers(grey, dictionary, corners, ids, parameters);
  std::vector<Eigen::Vector2d> found;
  int matches = 0;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (ids[i] != id) continue;
    ++matches;
    found.clear();
    for (const cv::Point2f& p : corners[i]) found.emplace_back(p.x, p.y);
  }
  if (matches != 1 || found.size() != 4) return {};
  return refine_corners_by_edges(grey, found);
}

}  // namespace

int run_sim_observations(const SimObservationsOptions& options, std::ostream& out,
                         std::ostream& err) {
  if (options.configs < 1 || options.configs > 500)
    return fail(err, "--configs " + std::to_string(options.configs) + " is outside 1..500");
  if (options.output.empty())
    return fail(err, "-o: give the observations file to write, e.g. -o obs.yaml");
  if (Status s = check_output_path(options.output, "-o"); !s) return fail(err, s.error().message);
  if (!(options.noise >= 0.0 && options.noise <= 50.0))
    return fail(err, "--noise must be within 0..50 grey levels");
  if (options.supersample < 1 || options.supersample > 8)
    return fail(err, "--supersample must be within 1..8");

  auto rig = sim::load_stereo_rig(options.rig);
  if (!rig) return fail(err, "--rig: " + rig.error().message);
  auto model = load_robot(options.robot);
  if (!model) return fail(err, "--robot: " + model.error().message);
  auto body = rig->body_file.empty() ? body_description_for(**model)
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

  const RobotModel& robot = **model;
  std::mt19937_64 rng(options.seed);

  RegistrationObservations observations;
  observations.robot = options.robot;
  observations.point_in_flange.assign(marker.corners_flange.begin(), marker.corners_flange.end());
  const double min_cos = std::cos(radians_from_degrees(options.max_view_angle_deg));
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
      q = random_configuration(robot, rng);
      scene->set_configuration(q);
    } while (!marker_well_seen(*scene, min_cos, options.margin_px));

    ObservedConfiguration observed;
    observed.q = q;
    const auto frame = static_cast<std::uint64_t>(c);
    observed.left_pixels = detect_marker(scene->render(sim::Eye::kLeft, frame), marker.spec.id);
    observed.right_pixels = detect_marker(scene->render(sim::Eye::kRight, frame), marker.spec.id);
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
  if (Status s = write_observations_file(observations, options.output); !s) {
    return fail(err, s.error().message, 1);
  }
  out << "wrote " << observations.configurations.size() << " configurations to " << options.output;
  if (skipped > 0) out << " (" << skipped << " skipped: marker not detected)";
  out << "\n";
  return 0;
}

}  // namespace telear::cli
