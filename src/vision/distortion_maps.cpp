#include "telear/vision/distortion_maps.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "telear/vision/opencv_camera.hpp"

namespace telear::vision {

UndistortMaps compute_undistort_maps(const CameraModel& camera) {
  UndistortMaps maps;
  const cv::Size size(camera.width, camera.height);
  // OpenCV's map for the Brown-Conrady models (it ignores skew, hence the own loop with
  // alpha_c != 0); equidistant goes through the same loop, which evaluates telear's formulas.
  if (camera.alpha_c == 0.0 && camera.kc.model != DistortionModel::equidistant) {
    const cv::Matx33d K = opencv_camera_matrix(camera);
    cv::initUndistortRectifyMap(K, opencv_distortion(camera.kc), cv::noArray(), K, size, CV_32FC1,
                                maps.map_x, maps.map_y);
  } else {
    maps.map_x.create(size, CV_32FC1);
    maps.map_y.create(size, CV_32FC1);
    for (int v = 0; v < camera.height; ++v) {
      for (int u = 0; u < camera.width; ++u) {
        const Eigen::Vector2d raw =
            camera.pixel_from_normalized(camera.distort(camera.normalized_from_pixel({u, v})));
        maps.map_x.at<float>(v, u) = static_cast<float>(raw.x());
        maps.map_y.at<float>(v, u) = static_cast<float>(raw.y());
      }
    }
  }
  const double r_max = camera.max_monotonic_radius();
  if (std::isfinite(r_max)) {
    for (int v = 0; v < camera.height; ++v) {
      for (int u = 0; u < camera.width; ++u) {
        if (camera.normalized_from_pixel({u, v}).norm() > r_max) {
          maps.map_x.at<float>(v, u) = -1.0f;
          maps.map_y.at<float>(v, u) = -1.0f;
        }
      }
    }
  }
  return maps;
}

cv::Mat undistort_image(const cv::Mat& raw, const UndistortMaps& maps) {
  cv::Mat undistorted;
  cv::remap(raw, undistorted, maps.map_x, maps.map_y, cv::INTER_LINEAR, cv::BORDER_CONSTANT,
            cv::Scalar::all(0));
  return undistorted;
}

RawToPinholeLut compute_raw_to_pinhole_lut(const CameraModel& camera) {
  RawToPinholeLut lut;
  lut.pinhole_uv.create(camera.height, camera.width, CV_32FC2);
  constexpr double kInf = std::numeric_limits<double>::infinity();
  double min_u = kInf, min_v = kInf, max_u = -kInf, max_v = -kInf;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const double max_radius = camera.max_monotonic_radius();
  for (int v = 0; v < camera.height; ++v) {
    for (int u = 0; u < camera.width; ++u) {
      const std::optional<Eigen::Vector2d> p = camera.undistort_pixel_within({u, v}, max_radius);
      cv::Vec2f& out = lut.pinhole_uv.at<cv::Vec2f>(v, u);
      if (!p) {
        out = {nan, nan};
        ++lut.invalid_count;
        continue;
      }
      out = {static_cast<float>(p->x()), static_cast<float>(p->y())};
      min_u = std::min(min_u, p->x());
      max_u = std::max(max_u, p->x());
      min_v = std::min(min_v, p->y());
      max_v = std::max(max_v, p->y());
    }
  }
  if (min_u <= max_u) {
    lut.min_u = min_u;
    lut.max_u = max_u;
    lut.min_v = min_v;
    lut.max_v = max_v;
  }
  return lut;
}

}  // namespace telear::vision
