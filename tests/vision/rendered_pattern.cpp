#include "rendered_pattern.hpp"

#include <cmath>

namespace telear::test {
namespace {

constexpr int kSamples = 6;  // per pixel side

// Ideal reflectance of the target at (x, y) metres: 0 black, 1 white, -1 off the target.
double target_value(const vision::CalibrationPattern& p, double x, double y) {
  const double s = p.spacing;
  if (p.kind == vision::PatternKind::kChessboard) {
    if (x < -2 * s || y < -2 * s || x > (p.cols + 1) * s || y > (p.rows + 1) * s) return -1.0;
    if (x < -s || y < -s || x > p.cols * s || y > p.rows * s) return 1.0;  // white margin
    const auto i = static_cast<long>(std::floor(x / s));
    const auto j = static_cast<long>(std::floor(y / s));
    return (i + j) % 2 == 0 ? 0.0 : 1.0;
  }
  const double width = (2 * p.cols - 1) * s;
  if (x < -1.5 * s || y < -1.5 * s || x > width + 1.5 * s || y > (p.rows - 1) * s + 1.5 * s) {
    return -1.0;
  }
  const double radius = 0.35 * s;
  for (long r = static_cast<long>(std::floor(y / s)); r <= static_cast<long>(std::ceil(y / s));
       ++r) {
    if (r < 0 || r >= p.rows) continue;
    const long c = std::lround((x / s - static_cast<double>(r % 2)) / 2.0);
    if (c < 0 || c >= p.cols) continue;
    const double cx = (2 * c + r % 2) * s, cy = r * s;
    if (std::hypot(x - cx, y - cy) <= radius) return 0.0;
  }
  return 1.0;
}

}  // namespace

cv::Mat render_pattern(const vision::CalibrationPattern& pattern, const cv::Matx33d& H_pixel_target,
                       cv::Size size) {
  const cv::Matx33d H_target_pixel = H_pixel_target.inv();
  cv::Mat image(size, CV_8UC1);
  for (int v = 0; v < size.height; ++v) {
    for (int u = 0; u < size.width; ++u) {
      double sum = 0.0;
      for (int a = 0; a < kSamples; ++a) {
        for (int b = 0; b < kSamples; ++b) {
          // Pixel (u, v) covers [u - 0.5, u + 0.5) x [v - 0.5, v + 0.5).
          const cv::Vec3d q(u - 0.5 + (a + 0.5) / kSamples, v - 0.5 + (b + 0.5) / kSamples, 1.0);
          const cv::Vec3d t = H_target_pixel * q;
          const double value = target_value(pattern, t[0] / t[2], t[1] / t[2]);
          sum += value < 0.0 ? 0.5 : value;
        }
      }
      image.at<unsigned char>(v, u) =
          static_cast<unsigned char>(std::lround(30.0 + 190.0 * sum / (kSamples * kSamples)));
    }
  }
  return image;
}

std::vector<cv::Point2d> true_image_points(const vision::CalibrationPattern& pattern,
                                           const cv::Matx33d& H_pixel_target) {
  std::vector<cv::Point2d> points;
  for (const cv::Point3f& p : vision::pattern_object_points(pattern)) {
    const cv::Vec3d q = H_pixel_target * cv::Vec3d(p.x, p.y, 1.0);
    points.emplace_back(q[0] / q[2], q[1] / q[2]);
  }
  return points;
}

cv::Matx33d view_homography(const vision::CalibrationPattern& pattern, cv::Size size,
                            double width_px, double tilt_deg, double roll_deg) {
  const double f = 800.0;
  const cv::Matx33d K(f, 0, (size.width - 1) / 2.0, 0, f, (size.height - 1) / 2.0, 0, 0, 1);
  const double extent_x = pattern.kind == vision::PatternKind::kChessboard
                              ? (pattern.cols - 1) * pattern.spacing
                              : (2 * pattern.cols - 1) * pattern.spacing;
  const double extent_y = (pattern.rows - 1) * pattern.spacing;
  const double z = f * extent_x / width_px;
  const double t = tilt_deg * M_PI / 180.0, r = roll_deg * M_PI / 180.0;
  const cv::Matx33d Ry(std::cos(t), 0, std::sin(t), 0, 1, 0, -std::sin(t), 0, std::cos(t));
  const cv::Matx33d Rz(std::cos(r), -std::sin(r), 0, std::sin(r), std::cos(r), 0, 0, 0, 1);
  const cv::Matx33d R = Rz * Ry;
  const cv::Vec3d centre(extent_x / 2.0, extent_y / 2.0, 0.0);
  const cv::Vec3d translation = cv::Vec3d(0, 0, z) - R * centre;
  const cv::Matx33d Rt(R(0, 0), R(0, 1), translation[0], R(1, 0), R(1, 1), translation[1], R(2, 0),
                       R(2, 1), translation[2]);
  return K * Rt;
}

}  // namespace telear::test
