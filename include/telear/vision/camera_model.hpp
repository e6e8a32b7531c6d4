#pragma once
// A calibrated camera: a pinhole with lens distortion in one of the three models ROS's
// camera_info names (sensor_msgs/distortion_models.h), each equal to its OpenCV counterpart:
//
//   plumb_bob            Brown-Conrady, Bouguet's toolbox (the seed's fc, cc, alpha_c, kc) and
//                        cv::calibrateCamera's default: D = (k1, k2, p1, p2, k3)
//   rational_polynomial  cv::CALIB_RATIONAL_MODEL, for wide-angle lenses:
//                        D = (k1, k2, p1, p2, k3, k4, k5, k6)
//   equidistant          cv::fisheye (Kannala-Brandt, theta_d = f(theta)): D = (k1, k2, k3, k4)
//
// A point p_base in the robot base frame goes to the camera frame by p_cam = T_cam_base *
// p_base. The camera frame is OpenCV's: x right, y down, z forward along the optical axis.
//
//   normalized pinhole    x = p_cam.x / p_cam.z,   y = p_cam.y / p_cam.z,   r^2 = x^2 + y^2
//   plumb_bob             radial = 1 + k1 r^2 + k2 r^4 + k3 r^6
//   rational_polynomial   radial = (1 + k1 r^2 + k2 r^4 + k3 r^6) / (1 + k4 r^2 + k5 r^4 + k6 r^6)
//   (both)                xd = x radial + 2 p1 x y + p2 (r^2 + 2 x^2)
//                         yd = y radial + p1 (r^2 + 2 y^2) + 2 p2 x y
//   equidistant           theta = atan(r),  theta_d = theta (1 + k1 theta^2 + k2 theta^4 +
//                         k3 theta^6 + k4 theta^8),  (xd, yd) = (theta_d / r) (x, y)
//   pixel (fc, cc, skew)  u = fx (xd + alpha_c yd) + cx,   v = fy yd + cy
//
// i.e. [u v 1]^T = K [xd yd 1]^T with K = [fx, alpha_c fx, cx; 0, fy, cy; 0, 0, 1].
// Pixel coordinates follow OpenCV: the centre of the top-left pixel is (0, 0), u grows to the
// right and v downwards; pixel (i, j) covers [i - 0.5, i + 0.5) x [j - 0.5, j + 0.5).
//
// Skew and OpenCV: cv::projectPoints and cv::initUndistortRectifyMap read only fx, fy, cx and
// cy from the camera matrix and ignore K(0,1) (checked on OpenCV 4.6: projecting (0.1, 0.2, 1)
// with K(0,1) = 0 and with K(0,1) = 50 gives the same pixel). With alpha_c = 0 -- which is all
// cv::calibrateCamera ever estimates -- this model equals cv::projectPoints (and
// cv::fisheye::projectPoints for equidistant) to rounding; with alpha_c != 0 it follows
// Bouguet's toolbox, which OpenCV's functions cannot express, and telear evaluates the
// formulas above itself.
//
// Distortion is a polynomial (or a ratio of them): far enough from the centre it folds back
// (with plumb_bob k1 = -0.3 and nothing else, rays beyond r = 1.054 land closer to the centre
// again). max_monotonic_radius() is where the radial part stops growing; undistort() refuses
// points beyond it. The pinhole projection needs p_cam.z > 0, so an equidistant camera is used
// up to (not including) a 180 degree field of view.

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <optional>
#include <string_view>
#include <vector>

#include "telear/core/result.hpp"

namespace telear::vision {

enum class DistortionModel { plumb_bob, rational_polynomial, equidistant };

// The ROS name ("plumb_bob", "rational_polynomial", "equidistant").
const char* distortion_model_name(DistortionModel model);
// A ROS name -> the model; "fisheye" (OpenCV's and Kalibr's word) is read as equidistant. The
// error lists the names accepted.
Result<DistortionModel> parse_distortion_model(std::string_view name);
// How many coefficients the model's D vector has: 5, 8 or 4.
std::size_t distortion_coefficient_count(DistortionModel model);

// The lens distortion: a model and its coefficients. The fields a model does not use stay 0
// (plumb_bob uses k1, k2, p1, p2, k3; rational_polynomial all eight; equidistant k1..k4).
struct Distortion {
  DistortionModel model = DistortionModel::plumb_bob;
  double k1 = 0.0, k2 = 0.0, p1 = 0.0, p2 = 0.0, k3 = 0.0, k4 = 0.0, k5 = 0.0, k6 = 0.0;

  bool is_zero() const {
    return k1 == 0.0 && k2 == 0.0 && p1 == 0.0 && p2 == 0.0 && k3 == 0.0 && k4 == 0.0 &&
           k5 == 0.0 && k6 == 0.0;
  }
  // The D vector in the model's own order (ROS camera_info's D, OpenCV's distCoeffs):
  // plumb_bob (k1, k2, p1, p2, k3); rational_polynomial (k1, k2, p1, p2, k3, k4, k5, k6);
  // equidistant (k1, k2, k3, k4).
  std::vector<double> coefficients() const;
  // The names of coefficients()' entries, in the same order.
  std::vector<const char*> coefficient_names() const;
  // A model and its D vector; the error says how many coefficients the model takes.
  static Result<Distortion> from_coefficients(DistortionModel model, const std::vector<double>& d);
  // plumb_bob from (k1, k2, p1, p2, k3).
  static Distortion plumb_bob(double k1, double k2, double p1, double p2, double k3) {
    Distortion d;
    d.k1 = k1, d.k2 = k2, d.p1 = p1, d.p2 = p2, d.k3 = k3;
    return d;
  }
};

// The distortion map of the header comment, normalized (x, y) -> (xd, yd), templated so that
// Ceres's automatic differentiation evaluates the same formulas the rest of telear uses.
template <typename T>
void distort_normalized(const Distortion& d, const T& x, const T& y, T& xd, T& yd) {
  using std::atan;
  using std::sqrt;
  const T r2 = x * x + y * y;
  if (d.model == DistortionModel::equidistant) {
    // theta_d / r -> 1 as r -> 0; below 1e-16 the series' first term is exact to rounding and
    // sqrt's derivative at 0 would poison automatic differentiation.
    if (r2 < T(1e-16)) {
      xd = x;
      yd = y;
      return;
    }
    const T r = sqrt(r2);
    const T theta = atan(r);
    const T t2 = theta * theta;
    const T theta_d =
        theta * (T(1.0) + t2 * (T(d.k1) + t2 * (T(d.k2) + t2 * (T(d.k3) + t2 * T(d.k4)))));
    const T scale = theta_d / r;
    xd = x * scale;
    yd = y * scale;
    return;
  }
  T radial = T(1.0) + r2 * (T(d.k1) + r2 * (T(d.k2) + r2 * T(d.k3)));
  if (d.model == DistortionModel::rational_polynomial) {
    radial /= T(1.0) + r2 * (T(d.k4) + r2 * (T(d.k5) + r2 * T(d.k6)));
  }
  xd = x * radial + T(2.0 * d.p1) * x * y + T(d.p2) * (r2 + T(2.0) * x * x);
  yd = y * radial + T(d.p1) * (r2 + T(2.0) * y * y) + T(2.0 * d.p2) * x * y;
}

struct CameraModel {
  int width = 0;              // image size, pixels
  int height = 0;             // image size, pixels
  double fx = 0.0, fy = 0.0;  // focal lengths, pixels (fc)
  double cx = 0.0, cy = 0.0;  // principal point, pixels (cc)
  double alpha_c = 0.0;       // skew coefficient (Bouguet); K(0,1) = alpha_c * fx
  Distortion kc;
  Eigen::Isometry3d T_cam_base = Eigen::Isometry3d::Identity();  // base frame -> camera, metres

  // The 3x3 camera matrix, skew included.
  Eigen::Matrix3d K() const;
  double skew() const { return alpha_c * fx; }  // K(0,1), pixels

  // Normalized pinhole coordinates -> distorted normalized coordinates (the formulas above).
  Eigen::Vector2d distort(const Eigen::Vector2d& x) const;
  // The inverse of distort() by Newton's method, to ~1e-14; nullopt when it does not converge
  // or the answer lies beyond max_monotonic_radius().
  std::optional<Eigen::Vector2d> undistort(const Eigen::Vector2d& xd) const;
  // The same with max_monotonic_radius() computed once by the caller (per-pixel loops).
  std::optional<Eigen::Vector2d> undistort_within(const Eigen::Vector2d& xd,
                                                  double max_radius) const;

  // Distorted normalized coordinates <-> pixels (K and its inverse).
  Eigen::Vector2d pixel_from_normalized(const Eigen::Vector2d& xd) const;
  Eigen::Vector2d normalized_from_pixel(const Eigen::Vector2d& uv) const;

  // Pixel of a point given in the base frame, with distortion (project) or without it
  // (project_pinhole: what the same K shows for an ideal lens). nullopt for points at or
  // behind the camera's z = 0 plane.
  std::optional<Eigen::Vector2d> project(const Eigen::Vector3d& p_base) const;
  std::optional<Eigen::Vector2d> project_pinhole(const Eigen::Vector3d& p_base) const;

  // A raw (distorted) image pixel -> where an ideal lens with the same K puts the same ray.
  std::optional<Eigen::Vector2d> undistort_pixel(const Eigen::Vector2d& uv_raw) const;
  std::optional<Eigen::Vector2d> undistort_pixel_within(const Eigen::Vector2d& uv_raw,
                                                        double max_radius) const;

  // Largest normalized radius up to which the radial part (r * radial(r), or theta_d(atan r)
  // for equidistant) increases (the model is invertible inside it); +infinity when it grows up
  // to r = 10 (84 degrees off axis).
  double max_monotonic_radius() const;
};

// A stereo pair: each camera carries its own T_cam_base.
struct StereoCameraModel {
  CameraModel left;
  CameraModel right;
};

// Checks values that came from a file or the network: positive image size (at most 16384),
// positive finite focal lengths, finite principal point, skew and distortion, and a rigid
// T_cam_base. The error names the field and says why.
Status validate_camera(const CameraModel& camera);

// The same camera seen through an image resized to width x height (a stream scaled by the
// vision server): pixel (i, j) of the new image covers [i, i + 1) / s of the old, so
// fx' = sx fx, cx' = sx (cx + 0.5) - 0.5 (likewise y); skew and distortion (which act on
// normalized coordinates) and the pose are unchanged. width, height > 0 (asserted).
CameraModel resized_camera(const CameraModel& camera, int width, int height);

// A distortion-free camera at `eye_base` looking at `target_base`, with `up_base` pointing up
// in the image, vertical field of view `vertical_fov` (rad), square pixels, centred
// principal point (cx = (width - 1) / 2). `eye_base` must differ from `target_base` and
// `up_base` must not be parallel to the viewing direction.
CameraModel look_at_camera(int width, int height, double vertical_fov,
                           const Eigen::Vector3d& eye_base, const Eigen::Vector3d& target_base,
                           const Eigen::Vector3d& up_base);

}  // namespace telear::vision
