// ChArUco corners seen through a lens (telear/vision/charuco_board.hpp, refine_charuco_corners):
// a lens bends the board's lines, and straight lines fitted through a corner's two edge halves
// cross beside it. Issue 26 item 1: on the simulated rig (k1 = -0.28) that put every board
// view's corners ~0.01-0.02 px towards the image centre -- the image of a lens with a focal
// length ~1e-4 shorter, so a board 2.3 m away was placed ~0.2-0.3 mm too far -- and the boards
// registered 0.19-0.36 mm off where the single marker gave 0.08-0.34 mm.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "synthetic_observations.hpp"
#include "telear/vision/camera_model.hpp"
#include "telear/vision/registration_target.hpp"

namespace telear::vision {
namespace {

// Inside an axis-aligned quadrilateral of the target's plane.
bool inside(const std::array<Eigen::Vector3d, 4>& q, double x, double y) {
  const double x0 = std::min(q[0].x(), q[2].x()), x1 = std::max(q[0].x(), q[2].x());
  const double y0 = std::min(q[0].y(), q[2].y()), y1 = std::max(q[0].y(), q[2].y());
  return x >= x0 && x < x1 && y >= y0 && y < y1;
}

// The target at pose (R, t) in the camera frame seen by `camera` (its T_cam_base the
// identity): each pixel the mean of ss x ss samples, each traced back through the lens onto
// the target's plane. Only the pixels around the target are drawn (mid-grey elsewhere).
cv::Mat render_through_lens(const RegistrationTarget& tg, const CameraModel& camera,
                            const Eigen::Matrix3d& R, const Eigen::Vector3d& t, int ss) {
  const auto quads = registration_target_dark_quads(tg);
  const Eigen::Vector2d half = 0.5 * tg.printed_size_m();
  cv::Mat out(camera.height, camera.width, CV_8UC1, cv::Scalar(128));
  double u0 = 1e9, v0 = 1e9, u1 = -1e9, v1 = -1e9;
  for (double sx : {-1.0, 1.0})
    for (double sy : {-1.0, 1.0}) {
      auto p = camera.project(R * Eigen::Vector3d(sx * half.x(), sy * half.y(), 0) + t);
      u0 = std::min(u0, p->x());
      u1 = std::max(u1, p->x());
      v0 = std::min(v0, p->y());
      v1 = std::max(v1, p->y());
    }
  const Eigen::Vector3d n = R.col(2);
  for (int v = std::max(0, int(v0) - 8); v < std::min(camera.height, int(v1) + 8); ++v) {
    for (int u = std::max(0, int(u0) - 8); u < std::min(camera.width, int(u1) + 8); ++u) {
      double sum = 0;
      for (int a = 0; a < ss; ++a) {
        for (int b = 0; b < ss; ++b) {
          const Eigen::Vector2d raw(u - 0.5 + (b + 0.5) / ss, v - 0.5 + (a + 0.5) / ss);
          const Eigen::Vector2d x =
              *camera.undistort_within(camera.normalized_from_pixel(raw), 10.0);
          const Eigen::Vector3d ray(x.x(), x.y(), 1.0);
          const double s = n.dot(t) / n.dot(ray);
          const Eigen::Vector3d p = R.transpose() * (s * ray - t);
          double r = 0.5;
          if (std::abs(p.x()) <= half.x() && std::abs(p.y()) <= half.y()) {
            r = 1.0;
            for (const auto& q : quads) {
              if (inside(q, p.x(), p.y())) {
                r = 0.0;
                break;
              }
            }
          }
          sum += r;
        }
      }
      out.at<std::uint8_t>(v, u) = cv::saturate_cast<std::uint8_t>(30 + 200 * sum / (ss * ss));
    }
  }
  return out;
}

TEST(TargetThroughLensTest, BoardCornersKeepTheirScaleAndPlaceThroughABarrelLens) {
  auto target = parse_registration_target("charuco:4x4:0.08:0.05:4x4_50");
  ASSERT_TRUE(target) << target.error().message;
  // The simulated rig's left camera (data/cameras/puma560_stereo.yaml: k1 = -0.281), in its
  // own frame; the board 2.3 m away (squares ~18 px) and 150 px from the image centre, turned
  // at random.
  CameraModel camera = test::shipped_stereo_cameras().left;
  camera.T_cam_base = Eigen::Isometry3d::Identity();
  const std::vector<Eigen::Vector3d> points = target->points();
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  double radial_sum = 0.0;
  int views = 0;
  for (int i = 0; i < 24; ++i) {
    const Eigen::Matrix3d R =
        (Eigen::AngleAxisd(3.14 * uniform(rng), Eigen::Vector3d::UnitZ()) *
         Eigen::AngleAxisd(0.5 * uniform(rng), Eigen::Vector3d::UnitX()) *
         Eigen::AngleAxisd(0.4 * uniform(rng), Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitX()))  // facing the camera
            .toRotationMatrix();
    const double z = 2.3, angle = std::numbers::pi * uniform(rng), radius = 150.0 / camera.fx * z;
    const Eigen::Vector3d t(radius * std::cos(angle), radius * std::sin(angle), z);
    const TargetDetection found =
        detect_registration_target(render_through_lens(*target, camera, R, t, 4), *target);
    if (found.ids.size() < 4) continue;
    // The detected corners' centre against their true projections' centre, along the image
    // radius.
    Eigen::Vector2d truth_centre = Eigen::Vector2d::Zero(), found_centre = truth_centre;
    for (std::size_t k = 0; k < found.ids.size(); ++k) {
      truth_centre += *camera.project(R * points[found.ids[k]] + t) / double(found.ids.size());
      found_centre += found.pixels[k] / static_cast<double>(found.ids.size());
    }
    const Eigen::Vector2d outwards =
        (truth_centre - Eigen::Vector2d(camera.cx, camera.cy)).normalized();
    radial_sum += (found_centre - truth_centre).dot(outwards);
    ++views;
  }
  ASSERT_GE(views, 16);
  // Straight lines (before): 0.016 px inwards. Tangents: 0.003 px.
  EXPECT_LT(std::abs(radial_sum / views), 0.006)
      << "mean offset along the radius (px), " << views << " views";
}

}  // namespace
}  // namespace telear::vision
