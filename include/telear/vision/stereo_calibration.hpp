#pragma once
// Stereo calibration: both cameras' intrinsics and the pose of the right camera relative to
// the left, from views of one pattern seen by both cameras at the same time.
//
// Geometry. A point X in the pattern frame of view i is, in the left camera, X_L = R_i X + t_i
// and, in the right camera, X_R = R X_L + T (OpenCV's stereoCalibrate convention: R, T map
// left-camera coordinates to right-camera coordinates; T is in the pattern's units, metres
// for telear). The baseline is |T|. E = [T]x R and F = K_R^-T E K_L^-1 are the essential and
// fundamental matrices (x_R^T F x_L = 0 for undistorted pixels).
//
// Procedure (docs/calibration.md has the measurements behind the choice):
//   1. each camera calibrated alone (cv::calibrateCamera) on the pairs, for initial values;
//   2. cv::stereoCalibrate with CALIB_USE_INTRINSIC_GUESS: a joint Levenberg-Marquardt
//      refinement of both cameras' intrinsics, R, T and the left poses over the reprojection
//      error in both images. It needs no more data than step 1 and couples the two cameras
//      through the rigid R, T, which gives smaller errors than keeping the mono intrinsics
//      fixed (options.refine_intrinsics = false: CALIB_FIX_INTRINSIC);
//   3. outliers: a pair whose error in either image exceeds outlier_factor x that camera's
//      median (and outlier_floor_px) is dropped, worst first, and steps 1-2 run again;
//   4. cv::stereoRectify (Bouguet's rectification, CALIB_ZERO_DISPARITY) for R1, R2, P1, P2, Q.
//
// The stereo RMS is stereoCalibrate's: sqrt(sum over both images of |residual|^2 / (2 N))
// for N points per camera. Standard deviations of every estimated parameter come from the
// Gauss-Newton covariance of the joint problem (both intrinsics, R as a rotation vector, T,
// every left pose): telear builds that Jacobian itself from cv::projectPoints and
// cv::composeRT derivatives, because stereoCalibrate does not report it.
//
// Output cameras: the base frame is the left camera's until registration replaces it, so
// left.T_cam_base = identity and right.T_cam_base = [R | T].

#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/vision/calibration_pattern.hpp"
#include "telear/vision/camera_model.hpp"
#include "telear/vision/mono_calibration.hpp"

namespace telear::vision {

// One view of the pattern seen by both cameras; points in pattern_object_points() order.
struct StereoPatternView {
  std::string left_name;
  std::string right_name;
  std::vector<cv::Point2f> left_points;
  std::vector<cv::Point2f> right_points;
  // Part of the pattern (ChArUco: the corners both images show): the points' positions on
  // the target, one per left / right point. Empty: pattern_object_points(), every point.
  std::vector<cv::Point3f> object_points = {};
};

struct StereoCalibrationOptions {
  CalibrationOptions calibration;  // outliers, minimum views, distortion terms (both cameras)
  bool refine_intrinsics = true;   // false: keep each camera's mono intrinsics fixed
  double rectify_alpha = 0.0;      // cv::stereoRectify alpha: 0 = only valid pixels, 1 = all

  Status validate() const;
};

struct StereoCalibratedView {
  std::string left_name;
  std::string right_name;
  double left_rms_px = 0.0;
  double right_rms_px = 0.0;
  Eigen::Isometry3d T_left_target = Eigen::Isometry3d::Identity();  // pattern -> left camera
};

struct StereoRectification {
  cv::Matx33d R1, R2;            // rotations taking each camera's frame to its rectified frame
  cv::Matx34d P1, P2;            // projections in the rectified frames (P2(0,3) = -f * baseline)
  cv::Matx44d Q;                 // disparity-to-depth mapping
  cv::Rect left_roi, right_roi;  // valid pixels of each rectified image
};

struct StereoCalibration {
  StereoCameraModel cameras;  // left.T_cam_base = I, right.T_cam_base = [R | T]
  IntrinsicsStdDev left_std_dev;
  IntrinsicsStdDev right_std_dev;
  cv::Matx33d R;  // left camera -> right camera
  cv::Vec3d T;    // pattern units (metres)
  cv::Matx33d E, F;
  Eigen::Vector3d rotation_std = Eigen::Vector3d::Zero();     // of R's rotation vector, rad
  Eigen::Vector3d translation_std = Eigen::Vector3d::Zero();  // of T, pattern units
  double baseline_std = 0.0;                                  // of |T|, first order
  StereoRectification rectification;
  double rms_px = 0.0;                      // both images together (stereoCalibrate's figure)
  double left_rms_px = 0.0;                 // left images only, same solution
  double right_rms_px = 0.0;                // right images only, same solution
  double mono_left_rms_px = 0.0;            // step 1, each camera alone, same views
  double mono_right_rms_px = 0.0;           // step 1, each camera alone, same views
  std::vector<StereoCalibratedView> views;  // the pairs used, in input order
  std::vector<RejectedView> rejected;       // outlier pairs, in rejection order

  double baseline() const { return cv::norm(T); }
};

// Calibrates a stereo pair. Errors: invalid options, malformed views, fewer than
// options.calibration.min_views pairs, or a solve that fails.
Result<StereoCalibration> calibrate_stereo(const CalibrationPattern& pattern,
                                           const std::vector<StereoPatternView>& views,
                                           cv::Size image_size,
                                           const StereoCalibrationOptions& options = {});

}  // namespace telear::vision
