#include "telear/vision/camera_model.hpp"

#include <cassert>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>

#include "telear/core/number_format.hpp"
#include "telear/core/pose.hpp"

namespace telear::vision {

Eigen::Matrix3d CameraModel::K() const {
  Eigen::Matrix3d K;
  K << fx, alpha_c * fx, cx, 0.0, fy, cy, 0.0, 0.0, 1.0;
  return K;
}

Eigen::Vector2d CameraModel::distort(const Eigen::Vector2d& p) const {
  const double x = p.x(), y = p.y();
  const double r2 = x * x + y * y;
  const double radial = 1.0 + r2 * (kc.k1 + r2 * (kc.k2 + r2 * kc.k3));
  return {x * radial + 2.0 * kc.p1 * x * y + kc.p2 * (r2 + 2.0 * x * x),
          y * radial + kc.p1 * (r2 + 2.0 * y * y) + 2.0 * kc.p2 * x * y};
}

std::optional<Eigen::Vector2d> CameraModel::undistort(const Eigen::Vector2d& xd) const {
  return undistort_within(xd, max_monotonic_radius());
}

std::optional<Eigen::Vector2d> CameraModel::undistort_within(const Eigen::Vector2d& xd,
                                                             double max_radius) const {
  if (kc.is_zero()) return xd;
  // Newton's method on distort(x) = xd from x = xd; the Jacobian is analytic. Inside the
  // monotonic radius the map is a smooth bijection close to the identity, so a handful of
  // iterations reach machine precision.
  Eigen::Vector2d p = xd;
  bool converged = false;
  for (int iteration = 0; iteration < 50; ++iteration) {
    const double x = p.x(), y = p.y();
    const double r2 = x * x + y * y;
    const double radial = 1.0 + r2 * (kc.k1 + r2 * (kc.k2 + r2 * kc.k3));
    const double dradial = kc.k1 + r2 * (2.0 * kc.k2 + 3.0 * r2 * kc.k3);  // d radial / d r2
    Eigen::Matrix2d J;
    J(0, 0) = radial + 2.0 * x * x * dradial + 2.0 * kc.p1 * y + 6.0 * kc.p2 * x;
    J(0, 1) = 2.0 * x * y * dradial + 2.0 * kc.p1 * x + 2.0 * kc.p2 * y;
    J(1, 0) = 2.0 * x * y * dradial + 2.0 * kc.p1 * x + 2.0 * kc.p2 * y;
    J(1, 1) = radial + 2.0 * y * y * dradial + 6.0 * kc.p1 * y + 2.0 * kc.p2 * x;
    const Eigen::Vector2d residual = distort(p) - xd;
    const double det = J.determinant();
    if (!(std::abs(det) > 1e-12)) return std::nullopt;
    const Eigen::Vector2d step = J.inverse() * residual;
    p -= step;
    if (!p.allFinite() || p.norm() > 1e3) return std::nullopt;
    if (step.norm() <= 1e-15 * (1.0 + p.norm())) {
      converged = true;
      break;
    }
  }
  if (!converged && (distort(p) - xd).norm() > 1e-12) return std::nullopt;
  if (p.norm() > max_radius) return std::nullopt;
  return p;
}

Eigen::Vector2d CameraModel::pixel_from_normalized(const Eigen::Vector2d& xd) const {
  return {fx * (xd.x() + alpha_c * xd.y()) + cx, fy * xd.y() + cy};
}

Eigen::Vector2d CameraModel::normalized_from_pixel(const Eigen::Vector2d& uv) const {
  const double yd = (uv.y() - cy) / fy;
  return {(uv.x() - cx) / fx - alpha_c * yd, yd};
}

std::optional<Eigen::Vector2d> CameraModel::project(const Eigen::Vector3d& p_base) const {
  const Eigen::Vector3d p_cam = T_cam_base * p_base;
  if (!(p_cam.z() > 0.0)) return std::nullopt;
  return pixel_from_normalized(distort(p_cam.head<2>() / p_cam.z()));
}

std::optional<Eigen::Vector2d> CameraModel::project_pinhole(const Eigen::Vector3d& p_base) const {
  const Eigen::Vector3d p_cam = T_cam_base * p_base;
  if (!(p_cam.z() > 0.0)) return std::nullopt;
  return pixel_from_normalized(p_cam.head<2>() / p_cam.z());
}

std::optional<Eigen::Vector2d> CameraModel::undistort_pixel(const Eigen::Vector2d& uv_raw) const {
  return undistort_pixel_within(uv_raw, max_monotonic_radius());
}

std::optional<Eigen::Vector2d> CameraModel::undistort_pixel_within(const Eigen::Vector2d& uv_raw,
                                                                   double max_radius) const {
  const std::optional<Eigen::Vector2d> x =
      undistort_within(normalized_from_pixel(uv_raw), max_radius);
  if (!x) return std::nullopt;
  return pixel_from_normalized(*x);
}

double CameraModel::max_monotonic_radius() const {
  // d/dr [r (1 + k1 r^2 + k2 r^4 + k3 r^6)] = 1 + 3 k1 r^2 + 5 k2 r^4 + 7 k3 r^6: find its first
  // zero on a fine grid, then refine by bisection.
  auto slope = [this](double r) {
    const double r2 = r * r;
    return 1.0 + r2 * (3.0 * kc.k1 + r2 * (5.0 * kc.k2 + r2 * 7.0 * kc.k3));
  };
  constexpr double kLimit = 10.0;
  constexpr int kSteps = 10000;
  double previous = 0.0;
  for (int i = 1; i <= kSteps; ++i) {
    const double r = kLimit * i / kSteps;
    if (slope(r) <= 0.0) {
      double lo = previous, hi = r;
      for (int k = 0; k < 60; ++k) {
        const double mid = 0.5 * (lo + hi);
        (slope(mid) > 0.0 ? lo : hi) = mid;
      }
      return lo;
    }
    previous = r;
  }
  return std::numeric_limits<double>::infinity();
}

Status validate_camera(const CameraModel& c) {
  constexpr int kMaxSize = 16384;
  if (c.width <= 0 || c.width > kMaxSize) {
    return Error{"image_width must be in [1, 16384], got " + std::to_string(c.width)};
  }
  if (c.height <= 0 || c.height > kMaxSize) {
    return Error{"image_height must be in [1, 16384], got " + std::to_string(c.height)};
  }
  if (!std::isfinite(c.fx) || c.fx <= 0.0) {
    return Error{"fx (camera_matrix[0][0]) must be positive and finite, got " +
                 core::format_number(c.fx, "%.9g")};
  }
  if (!std::isfinite(c.fy) || c.fy <= 0.0) {
    return Error{"fy (camera_matrix[1][1]) must be positive and finite, got " +
                 core::format_number(c.fy, "%.9g")};
  }
  if (!std::isfinite(c.cx)) return Error{"cx (camera_matrix[0][2]) must be finite"};
  if (!std::isfinite(c.cy)) return Error{"cy (camera_matrix[1][2]) must be finite"};
  if (!std::isfinite(c.alpha_c)) return Error{"skew (camera_matrix[0][1]) must be finite"};
  const std::array<double, 5> kc = c.kc.as_array();
  const char* names[5] = {"k1", "k2", "p1", "p2", "k3"};
  for (int i = 0; i < 5; ++i) {
    if (!std::isfinite(kc[static_cast<size_t>(i)])) {
      return Error{std::string("distortion_coefficients: ") + names[i] + " must be finite"};
    }
  }
  if (!core::is_valid_rigid_transform(c.T_cam_base.matrix(), 1e-6)) {
    return Error{
        "T_cam_base must be a rigid transform (orthonormal rotation with determinant +1, "
        "finite translation, last row 0 0 0 1)"};
  }
  return Status::Ok();
}

CameraModel look_at_camera(int width, int height, double vertical_fov,
                           const Eigen::Vector3d& eye_base, const Eigen::Vector3d& target_base,
                           const Eigen::Vector3d& up_base) {
  assert(width > 0 && height > 0 && vertical_fov > 0.0 && vertical_fov < std::numbers::pi);
  const Eigen::Vector3d z = (target_base - eye_base).normalized();  // forward
  Eigen::Vector3d x = z.cross(up_base);  // right: forward x up, since y points down
  assert(x.norm() > 1e-9 && "look_at_camera(): up is parallel to the viewing direction");
  x.normalize();
  const Eigen::Vector3d y = z.cross(x);  // down
  Eigen::Matrix3d R_base_cam;
  R_base_cam.col(0) = x;
  R_base_cam.col(1) = y;
  R_base_cam.col(2) = z;
  Eigen::Isometry3d T_base_cam = Eigen::Isometry3d::Identity();
  T_base_cam.linear() = R_base_cam;
  T_base_cam.translation() = eye_base;

  CameraModel camera;
  camera.width = width;
  camera.height = height;
  camera.fy = 0.5 * height / std::tan(0.5 * vertical_fov);
  camera.fx = camera.fy;
  camera.cx = 0.5 * (width - 1);
  camera.cy = 0.5 * (height - 1);
  camera.T_cam_base = T_base_cam.inverse();
  return camera;
}

CameraModel resized_camera(const CameraModel& camera, int width, int height) {
  assert(width > 0 && height > 0);
  const double sx = static_cast<double>(width) / camera.width;
  const double sy = static_cast<double>(height) / camera.height;
  CameraModel resized = camera;
  resized.width = width;
  resized.height = height;
  resized.fx = sx * camera.fx;
  resized.fy = sy * camera.fy;
  resized.cx = sx * (camera.cx + 0.5) - 0.5;
  resized.cy = sy * (camera.cy + 0.5) - 0.5;
  // alpha_c is unchanged: u = fx (x + alpha_c y) + cx scales as a whole with sx.
  return resized;
}

}  // namespace telear::vision
