#include "telear/vision/opencv_camera.hpp"

#include <opencv2/calib3d.hpp>

#include "telear/core/pose.hpp"

namespace telear::vision {

cv::Matx33d opencv_camera_matrix(const CameraModel& camera) {
  const Eigen::Matrix3d k = camera.K();
  cv::Matx33d K;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) K(r, c) = k(r, c);
  }
  return K;
}

cv::Mat opencv_distortion(const Distortion& distortion) {
  const std::vector<double> d = distortion.coefficients();
  cv::Mat out(1, static_cast<int>(d.size()), CV_64F);
  for (std::size_t i = 0; i < d.size(); ++i) out.at<double>(static_cast<int>(i)) = d[i];
  return out;
}

std::vector<cv::Point2d> opencv_project(const CameraModel& camera,
                                        const std::vector<Eigen::Vector3d>& points_base) {
  std::vector<cv::Point3d> object;
  object.reserve(points_base.size());
  for (const Eigen::Vector3d& p : points_base) object.emplace_back(p.x(), p.y(), p.z());
  const Eigen::Vector3d r = core::rotation_vector(camera.T_cam_base.linear());
  const Eigen::Vector3d t = camera.T_cam_base.translation();
  const cv::Vec3d rvec(r.x(), r.y(), r.z()), tvec(t.x(), t.y(), t.z());
  std::vector<cv::Point2d> pixels;
  if (object.empty()) return pixels;
  if (camera.kc.model == DistortionModel::equidistant) {
    cv::fisheye::projectPoints(object, pixels, rvec, tvec, opencv_camera_matrix(camera),
                               opencv_distortion(camera.kc), camera.alpha_c);
  } else {
    cv::projectPoints(object, rvec, tvec, opencv_camera_matrix(camera),
                      opencv_distortion(camera.kc), pixels);
  }
  return pixels;
}

}  // namespace telear::vision
