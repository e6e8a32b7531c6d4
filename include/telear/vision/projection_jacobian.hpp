#pragma once
// Reprojection residuals of one pattern view and their derivatives, for each lens model, in
// one parameter order -- the pieces of the Gauss-Newton covariances that calibration reports
// where OpenCV does not (cv::stereoCalibrate for every model, cv::fisheye::calibrate).
//
// OpenCV's two projection functions lay their Jacobians out differently:
//   cv::projectPoints            rvec(3) tvec(3) fx fy cx cy D(5 or 8)
//   cv::fisheye::projectPoints   fx fy cx cy D(4) rvec(3) tvec(3) alpha
// project_view() returns both as d_pose (rvec, tvec) and d_intrinsics (fx fy cx cy, then the
// model's D vector in Distortion::coefficients() order), so the covariance code is the same
// for every model.

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "telear/vision/camera_model.hpp"

namespace telear::vision {

// fx, fy, cx, cy and the model's coefficients: 9, 12 or 8.
inline int intrinsic_parameter_count(DistortionModel model) {
  return 4 + static_cast<int>(distortion_coefficient_count(model));
}

struct ViewProjection {
  Eigen::VectorXd residual;      // 2P: predicted - observed, (u, v) per point
  Eigen::MatrixXd d_pose;        // 2P x 6: rvec, tvec of the pose used
  Eigen::MatrixXd d_intrinsics;  // 2P x intrinsic_parameter_count(model)
};

// Projects `object` (pattern frame) with pose (rvec, tvec: 3x1 CV_64F) through K (3x3 CV_64F)
// and dist (the model's D vector, CV_64F) with OpenCV's function for `model`.
ViewProjection project_view(const std::vector<cv::Point3f>& object,
                            const std::vector<cv::Point2f>& observed, const cv::Mat& rvec,
                            const cv::Mat& tvec, const cv::Mat& K, const cv::Mat& dist,
                            DistortionModel model);

// The pose of the pattern in the camera (rvec, tvec, 3x1 CV_64F) from its image points, for
// any model: cv::solvePnP on the points, which for equidistant are first undistorted by
// cv::fisheye::undistortPoints (solvePnP knows only the Brown-Conrady models).
void solve_view_pose(const std::vector<cv::Point3f>& object, const std::vector<cv::Point2f>& image,
                     const cv::Mat& K, const cv::Mat& dist, DistortionModel model, cv::Mat& rvec,
                     cv::Mat& tvec);

// Cols x Rows CV_64F matrix -> Eigen.
Eigen::MatrixXd eigen_from_mat(const cv::Mat& m);

}  // namespace telear::vision
