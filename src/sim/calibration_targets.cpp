#include "telear/sim/calibration_targets.hpp"

#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>
#include <opencv2/aruco.hpp>
#include <random>

#include "telear/core/angles.hpp"

#include "target_print.hpp"

namespace telear::sim {
namespace {

// A quad with corners a, b, c, d (counter-clockwise seen from the side `normal` points to).
void add_quad(core::Mesh& mesh, const Eigen::Vector3f& a, const Eigen::Vector3f& b,
              const Eigen::Vector3f& c, const Eigen::Vector3f& d, const Eigen::Vector3f& normal,
              const Eigen::Vector3f& colour) {
  const std::uint32_t i0 = mesh.add_vertex(a, normal, colour);
  const std::uint32_t i1 = mesh.add_vertex(b, normal, colour);
  const std::uint32_t i2 = mesh.add_vertex(c, normal, colour);
  const std::uint32_t i3 = mesh.add_vertex(d, normal, colour);
  mesh.triangles.insert(mesh.triangles.end(), {i0, i1, i2, i0, i2, i3});
  mesh.lines.insert(mesh.lines.end(), {i0, i1, i1, i2, i2, i3, i3, i0});
}

// An axis-aligned rectangle [x0, x1] x [y0, y1] at height z of the target frame, facing -z.
void add_rect(core::Mesh& mesh, double x0, double y0, double x1, double y1, double z,
              const Eigen::Vector3f& colour) {
  const Eigen::Vector3f n(0.f, 0.f, -1.f);
  const auto p = [z](double x, double y) {
    return Eigen::Vector3f(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z));
  };
  // Seen from -z with x right, y down the winding (x0,y0) -> (x0,y1) -> (x1,y1) -> (x1,y0)
  // is counter-clockwise on screen.
  add_quad(mesh, p(x0, y0), p(x0, y1), p(x1, y1), p(x1, y0), n, colour);
}

}  // namespace

std::array<Eigen::Vector3d, 4> CalibrationTarget::outline_corners() const {
  return {Eigen::Vector3d(outline_min.x(), outline_min.y(), 0.0),
          Eigen::Vector3d(outline_max.x(), outline_min.y(), 0.0),
          Eigen::Vector3d(outline_max.x(), outline_max.y(), 0.0),
          Eigen::Vector3d(outline_min.x(), outline_max.y(), 0.0)};
}

Eigen::Vector3d CalibrationTarget::pattern_centre() const {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto& p : points_target) sum += p;
  return sum / static_cast<double>(points_target.size());
}

double CalibrationTarget::reflectance(double x, double y) const {
  if (x < outline_min.x() || y < outline_min.y() || x > outline_max.x() || y > outline_max.y()) {
    return -1.0;
  }
  const double s = pattern.spacing;
  switch (pattern.kind) {
    case vision::PatternKind::kChessboard: {
      if (x < -s || y < -s || x >= pattern.cols * s || y >= pattern.rows * s) return 1.0;
      const auto i = static_cast<long>(std::floor(x / s));
      const auto j = static_cast<long>(std::floor(y / s));
      return ((i + j) % 2 + 2) % 2 == 0 ? 0.0 : 1.0;
    }
    case vision::PatternKind::kAsymmetricCircles: {
      const auto r = std::lround(y / s);
      if (r < 0 || r >= pattern.rows) return 1.0;
      const auto c = std::lround((x / s - static_cast<double>(r % 2)) / 2.0);
      if (c < 0 || c >= pattern.cols) return 1.0;
      const double dx = x - static_cast<double>(2 * c + r % 2) * s,
                   dy = y - static_cast<double>(r) * s;
      return dx * dx + dy * dy <= 0.09 * s * s ? 0.0 : 1.0;
    }
    case vision::PatternKind::kCharuco:
      return charuco.reflectance(x, y);
  }
  return 1.0;
}

CalibrationTarget make_calibration_target(const vision::CalibrationPattern& pattern,
                                          double margin_squares) {
  CalibrationTarget target;
  target.pattern = pattern;
  for (const cv::Point3f& p : vision::pattern_object_points(pattern)) {
    target.points_target.emplace_back(p.x, p.y, p.z);
  }
  const double s = pattern.spacing;
  const double m = margin_squares * s;
  if (pattern.kind == vision::PatternKind::kChessboard) {
    // Squares from -s to cols * s (x) and -s to rows * s (y); margin outside that.
    const double x0 = -s, y0 = -s, x1 = pattern.cols * s, y1 = pattern.rows * s;
    for (int j = -1; j < pattern.rows; ++j) {
      for (int i = -1; i < pattern.cols; ++i) {
        const bool black = ((i + j) % 2 + 2) % 2 == 0;
        add_rect(target.mesh, i * s, j * s, (i + 1) * s, (j + 1) * s, 0.0, black ? kBlack : kWhite);
      }
    }
    // The white margin as four strips that do not overlap the squares.
    add_rect(target.mesh, x0 - m, y0 - m, x1 + m, y0, 0.0, kWhite);
    add_rect(target.mesh, x0 - m, y1, x1 + m, y1 + m, 0.0, kWhite);
    add_rect(target.mesh, x0 - m, y0, x0, y1, 0.0, kWhite);
    add_rect(target.mesh, x1, y0, x1 + m, y1, 0.0, kWhite);
    target.outline_min = {x0 - m, y0 - m};
    target.outline_max = {x1 + m, y1 + m};
  } else if (pattern.kind == vision::PatternKind::kCharuco) {
    target.charuco = vision::charuco_layout(pattern);
    const vision::CharucoLayout& layout = target.charuco;
    for (int j = 0; j < layout.squares_y; ++j) {
      for (int i = 0; i < layout.squares_x; ++i) {
        if (layout.black_square(i, j)) {
          add_rect(target.mesh, i * s, j * s, (i + 1) * s, (j + 1) * s, 0.0, kBlack);
        }
      }
    }
    for (const vision::CharucoMarker& marker : layout.markers) {
      const int n = marker.cells.rows;
      const double cell = marker.side / n;
      for (int row = 0; row < n; ++row) {
        for (int col = 0; col < n; ++col) {
          if (marker.cells.at<std::uint8_t>(row, col) > 127) continue;
          const double x = marker.top_left.x + col * cell, y = marker.top_left.y + row * cell;
          add_rect(target.mesh, x, y, x + cell, y + cell, 0.0, kBlack);
        }
      }
    }
    const double x1 = layout.squares_x * s, y1 = layout.squares_y * s;
    add_rect(target.mesh, -m, -m, x1 + m, y1 + m, 0.0002, kWhite);
    target.outline_min = {-m, -m};
    target.outline_max = {x1 + m, y1 + m};
  } else {
    const double radius = 0.3 * s;
    constexpr int kSegments = 96;
    for (const auto& centre : target.points_target) {
      std::vector<std::uint32_t> fan;
      const Eigen::Vector3f n(0.f, 0.f, -1.f);
      fan.push_back(target.mesh.add_vertex(centre.cast<float>(), n, kBlack));
      // Counter-clockwise on screen seen from -z (x right, y down): decreasing angle.
      for (int k = 0; k <= kSegments; ++k) {
        const double a = -2.0 * std::numbers::pi * k / kSegments;
        const Eigen::Vector3d p = centre + radius * Eigen::Vector3d(std::cos(a), std::sin(a), 0);
        fan.push_back(target.mesh.add_vertex(p.cast<float>(), n, kBlack));
      }
      target.mesh.append_triangle_fan(fan);
    }
    const double x0 = -m, y0 = -m;
    const double x1 = (2 * (pattern.cols - 1) + 1) * s + m, y1 = (pattern.rows - 1) * s + m;
    add_rect(target.mesh, x0, y0, x1, y1, 0.0002, kWhite);
    target.outline_min = {x0, y0};
    target.outline_max = {x1, y1};
  }
  return target;
}

TargetImageRenderer::TargetImageRenderer(const vision::CameraModel& camera)
    : camera_(camera), rays_(camera.height + 1, camera.width + 1, CV_64FC2) {
  const double max_radius = camera.max_monotonic_radius();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int v = 0; v <= camera.height; ++v) {
    for (int u = 0; u <= camera.width; ++u) {
      const auto x = camera.undistort_within(
          camera.normalized_from_pixel(Eigen::Vector2d(u - 0.5, v - 0.5)), max_radius);
      rays_.at<cv::Vec2d>(v, u) = x ? cv::Vec2d(x->x(), x->y()) : cv::Vec2d(nan, nan);
    }
  }
}

cv::Mat TargetImageRenderer::render(const CalibrationTarget& target,
                                    const Eigen::Isometry3d& T_base_target, int supersample,
                                    double noise_grey, std::uint64_t seed) const {
  assert(supersample >= 1 && supersample <= 8);
  // The target plane z = 0 maps to normalized image coordinates by M = [r1 r2 t]; a ray
  // (x, y, 1) meets it at M^-1 (x, y, 1), in front of the camera when the last entry is > 0.
  const Eigen::Isometry3d T_cam_target = camera_.T_cam_base * T_base_target;
  Eigen::Matrix3d M;
  M << T_cam_target.linear().col(0), T_cam_target.linear().col(1), T_cam_target.translation();
  const Eigen::Matrix3d M_inv = M.inverse();
  constexpr double kBlackGrey = 10.0, kWhiteGrey = 237.0, kBackgroundGrey = 128.0;
  const int n = supersample;
  cv::Mat image(camera_.height, camera_.width, CV_64FC1);
  for (int v = 0; v < camera_.height; ++v) {
    for (int u = 0; u < camera_.width; ++u) {
      const cv::Vec2d r00 = rays_.at<cv::Vec2d>(v, u), r01 = rays_.at<cv::Vec2d>(v, u + 1);
      const cv::Vec2d r10 = rays_.at<cv::Vec2d>(v + 1, u), r11 = rays_.at<cv::Vec2d>(v + 1, u + 1);
      double sum = 0.0;
      for (int b = 0; b < n; ++b) {
        const double fv = (b + 0.5) / n;
        for (int a = 0; a < n; ++a) {
          // The rays vary smoothly over a pixel: bilinear between its corners is exact to far
          // below the detectors' precision.
          const double fu = (a + 0.5) / n;
          const cv::Vec2d ray =
              (1 - fv) * ((1 - fu) * r00 + fu * r01) + fv * ((1 - fu) * r10 + fu * r11);
          double value = -1.0;
          if (std::isfinite(ray[0])) {
            const Eigen::Vector3d q = M_inv * Eigen::Vector3d(ray[0], ray[1], 1.0);
            if (q.z() > 0.0) value = target.reflectance(q.x() / q.z(), q.y() / q.z());
          }
          sum += value < 0.0 ? kBackgroundGrey : kBlackGrey + (kWhiteGrey - kBlackGrey) * value;
        }
      }
      image.at<double>(v, u) = sum / (n * n);
    }
  }
  if (noise_grey > 0.0) {
    cv::Mat noise(image.size(), CV_64FC1);
    cv::RNG rng(seed);
    rng.fill(noise, cv::RNG::NORMAL, 0.0, noise_grey);
    image += noise;
  }
  cv::Mat grey;
  image.convertTo(grey, CV_8UC1);  // rounds and saturates
  return grey;
}

Result<ArucoMarker> make_aruco_marker(const core::MarkerMount& spec) {
  if (spec.dictionary != "DICT_4X4_50") {
    return Error{"ArUco dictionary '" + spec.dictionary + "' is not supported (DICT_4X4_50)"};
  }
  if (spec.id < 0 || spec.id >= 50) {
    return Error{"ArUco marker id " + std::to_string(spec.id) +
                 " is outside DICT_4X4_50's range 0..49"};
  }
  if (!(spec.side_m > 0.0)) return Error{"ArUco marker side must be positive"};
  ArucoMarker marker;
  marker.mount = spec;
  // The 6 x 6 cells: 4 x 4 bits inside a one-cell black border (drawMarker, one pixel per
  // cell), then a one-cell white quiet zone around it: 8 x 8 cells.
  cv::Mat cells;
  cv::aruco::drawMarker(cv::aruco::getPredefinedDictionary(cv::aruco::DICT_4X4_50), spec.id, 6,
                        cells, 1);
  const double cell = spec.side_m / 6.0;
  core::Mesh face;
  const Eigen::Vector3f n(0.f, 0.f, 1.f);
  for (int row = -1; row <= 6; ++row) {
    for (int col = -1; col <= 6; ++col) {
      const bool inside = row >= 0 && row < 6 && col >= 0 && col < 6;
      const bool black = inside && cells.at<std::uint8_t>(row, col) < 128;
      // Cell (row, col) of the printed image: x = (col - 3) cell .. , y = (3 - row) cell ..
      const float xa = static_cast<float>((col - 3) * cell),
                  xb = static_cast<float>((col - 2) * cell);
      const float ya = static_cast<float>((3 - row) * cell),
                  yb = static_cast<float>((2 - row) * cell);
      // Counter-clockwise seen from +z (x right, y up).
      add_quad(face, {xa, yb, 0.f}, {xb, yb, 0.f}, {xb, ya, 0.f}, {xa, ya, 0.f}, n,
               black ? kBlack : kWhite);
    }
  }
  // Backing plate behind the face (z < 0), slightly larger than the quiet zone.
  const float half = static_cast<float>(4.5 * cell);
  core::append_box(face, Eigen::Vector3f(0.f, 0.f, -0.0051f),
                   Eigen::Vector3f(2 * half, 2 * half, 0.01f), Eigen::Vector3f(0.18f, 0.18f, 0.2f));
  face.transform(spec.T_flange_marker.matrix().cast<float>());
  marker.mesh = std::move(face);
  marker.corners_flange = spec.corners_flange();
  return marker;
}

namespace {

bool visible_in(const vision::CameraModel& camera, const Eigen::Isometry3d& T_base_target,
                const CalibrationTarget& target, double margin_px) {
  const Eigen::Isometry3d T_cam_target = camera.T_cam_base * T_base_target;
  // The printed face is seen from -z_target: the camera must be on that side.
  const Eigen::Vector3d camera_in_target = T_cam_target.inverse().translation();
  if (camera_in_target.z() >= 0.0) return false;
  const double max_radius = camera.max_monotonic_radius();
  const auto inside = [&](const Eigen::Vector3d& p_target) {
    const Eigen::Vector3d p_cam = T_cam_target * p_target;
    if (p_cam.z() <= 0.05) return false;
    if (std::hypot(p_cam.x() / p_cam.z(), p_cam.y() / p_cam.z()) >= 0.95 * max_radius) {
      return false;
    }
    const auto uv = camera.project(T_base_target * p_target);
    return uv && uv->x() >= margin_px - 0.5 && uv->y() >= margin_px - 0.5 &&
           uv->x() <= camera.width - 0.5 - margin_px && uv->y() <= camera.height - 0.5 - margin_px;
  };
  // Outline corners and points along its edges (a distorted edge bows between corners).
  const auto corners = target.outline_corners();
  for (int k = 0; k < 4; ++k) {
    for (int step = 0; step < 8; ++step) {
      const Eigen::Vector3d p = corners[k] + (corners[(k + 1) % 4] - corners[k]) * (step / 8.0);
      if (!inside(p)) return false;
    }
  }
  for (const auto& p : target.points_target) {
    if (!inside(p)) return false;
  }
  return true;
}

}  // namespace

Result<std::vector<Eigen::Isometry3d>> calibration_target_poses(
    const vision::StereoCameraModel& cameras, const Eigen::Isometry3d& T_base_rig,
    const CalibrationTarget& target, int count, std::uint64_t seed, double margin_px) {
  std::mt19937_64 generator(seed);
  const auto uniform = [&generator](double lo, double hi) {
    return lo + (hi - lo) * (static_cast<double>(generator() >> 11) / 9007199254740992.0);
  };
  const vision::CameraModel& left = cameras.left;
  const double board_width = target.outline_max.x() - target.outline_min.x();
  const Eigen::Vector3d centre_target =
      0.5 * (Eigen::Vector3d(target.outline_min.x(), target.outline_min.y(), 0.0) +
             Eigen::Vector3d(target.outline_max.x(), target.outline_max.y(), 0.0));
  std::vector<Eigen::Isometry3d> poses;
  for (int view = 0; view < count; ++view) {
    bool found = false;
    for (int attempt = 0; attempt < 2000 && !found; ++attempt) {
      const double fill = uniform(0.40, 0.70);
      const double distance = left.fx * board_width / (fill * left.width);
      const Eigen::Vector2d uv(uniform(0.3, 0.7) * left.width, uniform(0.3, 0.7) * left.height);
      const Eigen::Vector3d ray((uv.x() - left.cx) / left.fx, (uv.y() - left.cy) / left.fy, 1.0);
      const Eigen::Vector3d centre_rig = ray * distance;
      const double spin = core::radians_from_degrees(uniform(-20.0, 20.0));
      const double axis_angle = uniform(0.0, 2.0 * std::numbers::pi);
      const double tilt = core::radians_from_degrees(uniform(10.0, 40.0));
      const Eigen::Matrix3d R_rig_target =
          (Eigen::AngleAxisd(tilt, Eigen::Vector3d(std::cos(axis_angle), std::sin(axis_angle), 0)) *
           Eigen::AngleAxisd(spin, Eigen::Vector3d::UnitZ()))
              .toRotationMatrix();
      Eigen::Isometry3d T_rig_target = Eigen::Isometry3d::Identity();
      T_rig_target.linear() = R_rig_target;
      T_rig_target.translation() = centre_rig - R_rig_target * centre_target;
      const Eigen::Isometry3d T_base_target = T_base_rig * T_rig_target;
      if (visible_in(cameras.left, T_base_target, target, margin_px) &&
          visible_in(cameras.right, T_base_target, target, margin_px)) {
        poses.push_back(T_base_target);
        found = true;
      }
    }
    if (!found) {
      return Error{"no pose found that shows the whole " + target.pattern.spec() +
                   " target in both images (is the board too large for the cameras?)"};
    }
  }
  return poses;
}

}  // namespace telear::sim
