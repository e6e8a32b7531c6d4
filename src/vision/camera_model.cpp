#include "telear/vision/camera_model.hpp"

#include <algorithm>
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

const char* distortion_model_name(DistortionModel model) {
  switch (model) {
    case DistortionModel::plumb_bob:
      return "plumb_bob";
    case DistortionModel::rational_polynomial:
      return "rational_polynomial";
    case DistortionModel::equidistant:
      return "equidistant";
  }
  return "plumb_bob";
}

Result<DistortionModel> parse_distortion_model(std::string_view name) {
  if (name == "plumb_bob") return DistortionModel::plumb_bob;
  if (name == "rational_polynomial") return DistortionModel::rational_polynomial;
  if (name == "equidistant" || name == "fisheye") return DistortionModel::equidistant;
  return Error{"unknown distortion model '" + std::string(name) +
               "' (expected plumb_bob, rational_polynomial or equidistant)"};
}

std::size_t distortion_coefficient_count(DistortionModel model) {
  switch (model) {
    case DistortionModel::plumb_bob:
      return 5;
    case DistortionModel::rational_polynomial:
      return 8;
    case DistortionModel::equidistant:
      return 4;
  }
  return 5;
}

std::vector<double> Distortion::coefficients() const {
  switch (model) {
    case DistortionModel::plumb_bob:
      return {k1, k2, p1, p2, k3};
    case DistortionModel::rational_polynomial:
      return {k1, k2, p1, p2, k3, k4, k5, k6};
    case DistortionModel::equidistant:
      return {k1, k2, k3, k4};
  }
  return {};
}

std::vector<const char*> Distortion::coefficient_names() const {
  switch (model) {
    case DistortionModel::plumb_bob:
      return {"k1", "k2", "p1", "p2", "k3"};
    case DistortionModel::rational_polynomial:
      return {"k1", "k2", "p1", "p2", "k3", "k4", "k5", "k6"};
    case DistortionModel::equidistant:
      return {"k1", "k2", "k3", "k4"};
  }
  return {};
}

Result<Distortion> Distortion::from_coefficients(DistortionModel model,
                                                 const std::vector<double>& d) {
  const std::size_t expected = distortion_coefficient_count(model);
  // plumb_bob files often carry only (k1, k2, p1, p2): OpenCV and ROS read k3 = 0 then.
  const bool short_plumb_bob = model == DistortionModel::plumb_bob && d.size() == 4;
  if (d.size() != expected && !short_plumb_bob) {
    return Error{std::string(distortion_model_name(model)) + " takes " + std::to_string(expected) +
                 " distortion coefficients, got " + std::to_string(d.size())};
  }
  Distortion out;
  out.model = model;
  if (model == DistortionModel::equidistant) {
    out.k1 = d[0], out.k2 = d[1], out.k3 = d[2], out.k4 = d[3];
    return out;
  }
  out.k1 = d[0], out.k2 = d[1], out.p1 = d[2], out.p2 = d[3];
  if (d.size() > 4) out.k3 = d[4];
  if (model == DistortionModel::rational_polynomial) out.k4 = d[5], out.k5 = d[6], out.k6 = d[7];
  return out;
}

Eigen::Vector2d CameraModel::distort(const Eigen::Vector2d& p) const {
  Eigen::Vector2d out;
  distort_normalized(kc, p.x(), p.y(), out.x(), out.y());
  return out;
}

std::optional<Eigen::Vector2d> CameraModel::undistort(const Eigen::Vector2d& xd) const {
  return undistort_within(xd, max_monotonic_radius());
}

namespace {

// theta_d(theta) of the equidistant model and its derivative.
double equidistant_theta_d(const Distortion& d, double theta) {
  const double t2 = theta * theta;
  return theta * (1.0 + t2 * (d.k1 + t2 * (d.k2 + t2 * (d.k3 + t2 * d.k4))));
}
double equidistant_theta_d_slope(const Distortion& d, double theta) {
  const double t2 = theta * theta;
  return 1.0 + t2 * (3.0 * d.k1 + t2 * (5.0 * d.k2 + t2 * (7.0 * d.k3 + t2 * 9.0 * d.k4)));
}

// The equidistant model is radial only: solve theta_d(theta) = |xd| for theta by Newton's
// method (from theta = |xd|), then r = tan(theta) along xd's direction.
std::optional<Eigen::Vector2d> undistort_equidistant(const Distortion& d, const Eigen::Vector2d& xd,
                                                     double max_radius) {
  const double rd = xd.norm();
  if (rd < 1e-16) return xd;
  constexpr double kHalfPi = std::numbers::pi / 2.0;
  double theta = std::min(rd, kHalfPi - 1e-9);
  bool converged = false;
  for (int iteration = 0; iteration < 50; ++iteration) {
    const double slope = equidistant_theta_d_slope(d, theta);
    if (!(std::abs(slope) > 1e-12)) return std::nullopt;
    const double step = (equidistant_theta_d(d, theta) - rd) / slope;
    theta -= step;
    if (!std::isfinite(theta) || theta <= 0.0 || theta >= kHalfPi) return std::nullopt;
    if (std::abs(step) <= 1e-15 * (1.0 + theta)) {
      converged = true;
      break;
    }
  }
  if (!converged && std::abs(equidistant_theta_d(d, theta) - rd) > 1e-12) return std::nullopt;
  const double r = std::tan(theta);
  if (r > max_radius) return std::nullopt;
  return xd * (r / rd);
}

}  // namespace

std::optional<Eigen::Vector2d> CameraModel::undistort_within(const Eigen::Vector2d& xd,
                                                             double max_radius) const {
  if (kc.is_zero()) return xd;
  if (kc.model == DistortionModel::equidistant) return undistort_equidistant(kc, xd, max_radius);
  // Newton's method on distort(x) = xd from x = xd. The Jacobian is analytic for plumb_bob and
  // by central differences for rational_polynomial (an approximate Jacobian only slows the
  // last iterations: the residual itself is exact). Inside the monotonic radius the map is a
  // smooth bijection close to the identity, so a handful of iterations reach machine precision.
  Eigen::Vector2d p = xd;
  bool converged = false;
  for (int iteration = 0; iteration < 50; ++iteration) {
    const double x = p.x(), y = p.y();
    Eigen::Matrix2d J;
    if (kc.model == DistortionModel::plumb_bob) {
      const double r2 = x * x + y * y;
      const double radial = 1.0 + r2 * (kc.k1 + r2 * (kc.k2 + r2 * kc.k3));
      const double dradial = kc.k1 + r2 * (2.0 * kc.k2 + 3.0 * r2 * kc.k3);  // d radial / d r2
      J(0, 0) = radial + 2.0 * x * x * dradial + 2.0 * kc.p1 * y + 6.0 * kc.p2 * x;
      J(0, 1) = 2.0 * x * y * dradial + 2.0 * kc.p1 * x + 2.0 * kc.p2 * y;
      J(1, 0) = J(0, 1);
      J(1, 1) = radial + 2.0 * y * y * dradial + 6.0 * kc.p1 * y + 2.0 * kc.p2 * x;
    } else {
      constexpr double h = 1e-7;
      J.col(0) = (distort({x + h, y}) - distort({x - h, y})) / (2.0 * h);
      J.col(1) = (distort({x, y + h}) - distort({x, y - h})) / (2.0 * h);
    }
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
  // Find the first place where the radial map stops increasing on a fine grid, then refine by
  // bisection. plumb_bob: d/dr [r (1 + k1 r^2 + k2 r^4 + k3 r^6)] = 1 + 3 k1 r^2 + 5 k2 r^4 +
  // 7 k3 r^6. rational_polynomial: the derivative of r * radial(r) by central differences.
  // equidistant: d theta_d / d theta on theta in (0, pi/2), returned as r = tan(theta).
  // static: a generic lambda may use it without capturing it (clang requires it, GCC does not).
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  auto first_non_increasing = [](auto slope, double limit) {
    constexpr int kSteps = 10000;
    double previous = 0.0;
    for (int i = 1; i <= kSteps; ++i) {
      const double r = limit * i / kSteps;
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
    return kInf;
  };
  switch (kc.model) {
    case DistortionModel::plumb_bob:
      return first_non_increasing(
          [this](double r) {
            const double r2 = r * r;
            return 1.0 + r2 * (3.0 * kc.k1 + r2 * (5.0 * kc.k2 + r2 * 7.0 * kc.k3));
          },
          10.0);
    case DistortionModel::rational_polynomial:
      return first_non_increasing(
          [this](double r) {
            // The denominator crossing zero is a pole: the map is unusable beyond it too.
            auto denominator = [this](double s) {
              const double s2 = s * s;
              return 1.0 + s2 * (kc.k4 + s2 * (kc.k5 + s2 * kc.k6));
            };
            auto radial_map = [this, &denominator](double s) {
              const double s2 = s * s;
              return s * (1.0 + s2 * (kc.k1 + s2 * (kc.k2 + s2 * kc.k3))) / denominator(s);
            };
            if (denominator(r) <= 0.0) return -1.0;
            constexpr double h = 1e-7;
            return (radial_map(r + h) - radial_map(std::max(0.0, r - h))) /
                   (r + h - std::max(0.0, r - h));
          },
          10.0);
    case DistortionModel::equidistant: {
      const double theta = first_non_increasing(
          [this](double t) { return equidistant_theta_d_slope(kc, t); }, std::numbers::pi / 2.0);
      return std::isfinite(theta) ? std::tan(theta) : kInf;
    }
  }
  return kInf;
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
  const std::vector<double> kc = c.kc.coefficients();
  const std::vector<const char*> names = c.kc.coefficient_names();
  for (std::size_t i = 0; i < kc.size(); ++i) {
    if (!std::isfinite(kc[i])) {
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
