#pragma once
// Single-camera calibration (Zhang's planar method as implemented by cv::calibrateCamera:
// closed-form initialisation from the views' homographies, then Levenberg-Marquardt over
// the intrinsics and every view's pose, minimising the squared reprojection error).
//
// Input is a list of views of one calibration pattern: for each view the pixel positions of
// the pattern's points in the order of pattern_object_points(). They can come from images
// (telear/vision/calibration_images.hpp) or from anywhere else (simulation, a file of corners).
//
// Lens models (options.model, the ROS names of include/telear/vision/camera_model.hpp):
//   plumb_bob            cv::calibrateCamera: fx, fy, cx, cy and kc = (k1, k2, p1, p2), k3 held
//                        at 0 unless options.fix_k3 is false (below);
//   rational_polynomial  cv::calibrateCamera with CALIB_RATIONAL_MODEL: fx, fy, cx, cy and all
//                        eight of (k1, k2, p1, p2, k3, k4, k5, k6) (fix_k3 does not apply: the
//                        denominator's terms are what the model is chosen for);
//   equidistant          cv::fisheye::calibrate (CALIB_RECOMPUTE_EXTRINSIC | CALIB_FIX_SKEW):
//                        fx, fy, cx, cy and (k1, k2, k3, k4). OpenCV does not return its
//                        standard deviations, so telear computes them (below).
// Skew alpha_c is 0 (OpenCV does not estimate it, and modern sensors
// have square pixel grids). k3 is held by default, as Bouguet's toolbox does: with views of
// a 9x6 board it is poorly determined (sigma ~ 0.3) and trades off against k2, and on the
// synthetic rig a free k3 made the distortion worse away from the observed corners even when
// the true k3 was +-0.1 (max full-image mapping error 1.1-1.3 px vs 0.8-0.9 px held,
// docs/calibration.md). The tangential terms may be held at 0 too.
//
// Error measures, in pixels:
//   per view   rms_i = sqrt( sum_j |u_ij - proj(X_j)|^2 / n_i )       (n_i points of view i)
//   overall    rms   = sqrt( sum_ij |u_ij - proj(X_j)|^2 / sum_i n_i )
// Standard deviations are 1-sigma from the Gauss-Newton covariance sigma^2 (J^T J)^-1 with
// sigma^2 = (sum of squared residual components) / (residual components - free parameters),
// as OpenCV computes them for cv::calibrateCamera; for equidistant telear forms the same
// covariance itself from cv::fisheye::projectPoints' Jacobian (intrinsics and every pose).
//
// Outliers: after each solve the view with the largest rms_i is rejected and the problem
// solved again when rms_i > outlier_factor x median(rms) and rms_i > outlier_floor_px, as
// long as more than min_views views remain. One view per round, because one bad view
// inflates the others' errors too.

#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/vision/calibration_pattern.hpp"
#include "telear/vision/camera_model.hpp"

namespace telear::vision {

// One view of the pattern: its image points in pattern_object_points() order (pixels), or,
// for a view of part of the pattern (a ChArUco board partly out of frame), the points seen
// and their positions on the target in object_points.
struct PatternView {
  std::string name;  // e.g. the image file; used in reports
  std::vector<cv::Point2f> image_points;
  std::vector<cv::Point3f> object_points = {};  // empty: pattern_object_points(), every point
};

struct CalibrationOptions {
  DistortionModel model = DistortionModel::plumb_bob;  // the lens model to estimate
  double outlier_factor = 3.0;    // reject views with rms > factor x median; 0 keeps every view
  double outlier_floor_px = 0.1;  // ... and rms above this (no rejections among perfect views)
  int min_views = 3;              // fewer usable views is an error
  bool fix_k3 = true;             // plumb_bob: hold k3 at 0 (two radial terms; docs/calibration.md)
  bool zero_tangential = false;   // hold p1, p2 at 0 (not for equidistant, which has none)
  int max_iterations = 100;       // Levenberg-Marquardt iterations per solve

  // The error names the field and the violated constraint.
  Status validate() const;
};

// 1-sigma standard deviations of the intrinsics, in the units of the parameters (0 for a
// parameter held fixed).
struct IntrinsicsStdDev {
  double fx = 0.0, fy = 0.0, cx = 0.0, cy = 0.0;
  Distortion kc;
};

struct CalibratedView {
  std::string name;
  double rms_px = 0.0;
  Eigen::Isometry3d T_cam_target = Eigen::Isometry3d::Identity();  // pattern -> camera
  Eigen::Vector3d rotation_std = Eigen::Vector3d::Zero();          // of the rotation vector, rad
  Eigen::Vector3d translation_std = Eigen::Vector3d::Zero();       // pattern units
};

// A view left out, and why, in words ("outlier: 1.23 px > 3 x median 0.21 px").
struct RejectedView {
  std::string name;        // the image (mono) or the left image (stereo)
  std::string right_name;  // stereo: the right image; empty for mono
  std::string reason;
};

struct MonoCalibration {
  CameraModel camera;  // T_cam_base = identity (not registered to a robot)
  IntrinsicsStdDev std_dev;
  double rms_px = 0.0;
  std::vector<CalibratedView> views;   // the views used, in input order
  std::vector<RejectedView> rejected;  // outliers, in rejection order
};

// Checks that `views` fit `pattern` and `image_size`; the error says which view and why.
Status check_views(const std::vector<PatternView>& views, const CalibrationPattern& pattern,
                   cv::Size image_size);

// Calibrates one camera. Errors: invalid options, malformed views (see check_views), fewer
// than min_views views, or a solve that fails (degenerate views).
Result<MonoCalibration> calibrate_mono(const CalibrationPattern& pattern,
                                       const std::vector<PatternView>& views, cv::Size image_size,
                                       const CalibrationOptions& options = {});

// The flags the options select: cv::calibrateCamera's (plumb_bob, rational_polynomial) or
// cv::fisheye::calibrate's (equidistant).
int calibration_flags(const CalibrationOptions& options);

// The intrinsic parameters the options leave free, as indices into (fx, fy, cx, cy, then the
// model's D vector in Distortion::coefficients() order).
std::vector<int> free_intrinsic_parameters(const CalibrationOptions& options);

// Standard deviations in that order (0 for a fixed parameter) -> IntrinsicsStdDev of `model`.
IntrinsicsStdDev intrinsics_std_dev(const std::vector<double>& full, DistortionModel model);

// Median of a non-empty list of per-view errors.
double median_of(std::vector<double> values);

// The message for too few usable views (shared by mono and stereo).
std::string too_few_views_message(std::size_t usable, int needed, const std::string& what);

}  // namespace telear::vision
