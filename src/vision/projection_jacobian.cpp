#include "telear/vision/projection_jacobian.hpp"

#include <opencv2/calib3d.hpp>

namespace telear::vision {

Eigen::MatrixXd eigen_from_mat(const cv::Mat& m) {
  Eigen::MatrixXd e(m.rows, m.cols);
  for (int r = 0; r < m.rows; ++r) {
    for (int c = 0; c < m.cols; ++c) e(r, c) = m.at<double>(r, c);
  }
  return e;
}

ViewProjection project_view(const std::vector<cv::Point3f>& object,
                            const std::vector<cv::Point2f>& observed, const cv::Mat& rvec,
                            const cv::Mat& tvec, const cv::Mat& K, const cv::Mat& dist,
                            DistortionModel model) {
  std::vector<cv::Point2d> predicted;
  cv::Mat jacobian;
  const std::vector<cv::Point3d> object_d(object.begin(), object.end());
  const int intrinsics = intrinsic_parameter_count(model);
  ViewProjection p;
  if (model == DistortionModel::equidistant) {
    cv::fisheye::projectPoints(object_d, predicted, rvec, tvec, K, dist, 0.0, jacobian);
    const Eigen::MatrixXd J = eigen_from_mat(jacobian);
    p.d_intrinsics = J.leftCols(intrinsics);  // fx fy cx cy k1..k4
    p.d_pose = J.middleCols(intrinsics, 6);   // rvec tvec (alpha, the last column, is unused)
  } else {
    cv::projectPoints(object_d, rvec, tvec, K, dist, predicted, jacobian);
    const Eigen::MatrixXd J = eigen_from_mat(jacobian);
    p.d_pose = J.leftCols(6);
    p.d_intrinsics = J.middleCols(6, intrinsics);
  }
  const auto n = static_cast<Eigen::Index>(observed.size());
  p.residual.resize(2 * n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const auto k = static_cast<std::size_t>(j);
    p.residual(2 * j) = predicted[k].x - observed[k].x;
    p.residual(2 * j + 1) = predicted[k].y - observed[k].y;
  }
  return p;
}

void solve_view_pose(const std::vector<cv::Point3f>& object, const std::vector<cv::Point2f>& image,
                     const cv::Mat& K, const cv::Mat& dist, DistortionModel model, cv::Mat& rvec,
                     cv::Mat& tvec) {
  if (model == DistortionModel::equidistant) {
    std::vector<cv::Point2f> normalized;
    cv::fisheye::undistortPoints(image, normalized, K, dist);
    cv::solvePnP(object, normalized, cv::Matx33d::eye(), cv::noArray(), rvec, tvec);
  } else {
    cv::solvePnP(object, image, K, dist, rvec, tvec);
  }
  rvec.convertTo(rvec, CV_64F);
  tvec.convertTo(tvec, CV_64F);
}

}  // namespace telear::vision
