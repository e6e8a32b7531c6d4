#pragma once
// A calibrated camera: pinhole with Brown-Conrady lens distortion, the model of Bouguet's
// Camera Calibration Toolbox (the seed's fc, cc, alpha_c, kc) and of OpenCV's calib3d.
//
// A point p_base in the robot base frame goes to the camera frame by p_cam = T_cam_base *
// p_base. The camera frame is OpenCV's: x right, y down, z forward along the optical axis.
//
//   normalized pinhole    x = p_cam.x / p_cam.z,   y = p_cam.y / p_cam.z,   r^2 = x^2 + y^2
//   distortion (kc)       radial = 1 + k1 r^2 + k2 r^4 + k3 r^6
//                         xd = x radial + 2 p1 x y + p2 (r^2 + 2 x^2)
//                         yd = y radial + p1 (r^2 + 2 y^2) + 2 p2 x y
//   pixel (fc, cc, skew)  u = fx (xd + alpha_c yd) + cx,   v = fy yd + cy
//
// i.e. [u v 1]^T = K [xd yd 1]^T with K = [fx, alpha_c fx, cx; 0, fy, cy; 0, 0, 1].
// Pixel coordinates follow OpenCV: the centre of the top-left pixel is (0, 0), u grows to the
// right and v downwards; pixel (i, j) covers [i - 0.5, i + 0.5) x [j - 0.5, j + 0.5).
//
// Skew and OpenCV: cv::projectPoints and cv::initUndistortRectifyMap read only fx, fy, cx and
// cy from the camera matrix and ignore K(0,1) (checked on OpenCV 4.6: projecting (0.1, 0.2, 1)
// with K(0,1) = 0 and with K(0,1) = 50 gives the same pixel). With alpha_c = 0 -- which is all
// cv::calibrateCamera ever estimates -- this model equals cv::projectPoints to rounding; with
// alpha_c != 0 it follows Bouguet's toolbox, which OpenCV's functions cannot express, and
// telear evaluates the formulas above itself.
//
// Distortion is a polynomial: far enough from the centre it folds back (with k1 = -0.3 and
// nothing else, rays beyond r = 1.054 land closer to the centre again). max_monotonic_radius()
// is where the radial part stops growing; undistort() refuses points beyond it.

#include <Eigen/Geometry>
#include <array>
#include <optional>

#include "telear/core/result.hpp"

namespace telear::vision {

// Brown-Conrady coefficients in OpenCV's order (k1, k2, p1, p2, k3).
struct Distortion {
  double k1 = 0.0, k2 = 0.0, p1 = 0.0, p2 = 0.0, k3 = 0.0;

  bool is_zero() const { return k1 == 0.0 && k2 == 0.0 && p1 == 0.0 && p2 == 0.0 && k3 == 0.0; }
  std::array<double, 5> as_array() const { return {k1, k2, p1, p2, k3}; }
  static Distortion from_array(const std::array<double, 5>& kc) {
    return {kc[0], kc[1], kc[2], kc[3], kc[4]};
  }
};

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

  // Largest normalized radius up to which the radial part r * radial(r) increases (the
  // model is invertible inside it); +infinity when it grows up to r = 10.
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
