#include "telear/vision/distortion_maps.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace telear::vision {
namespace {

CameraModel lens_camera(double alpha_c = 0.0) {
  CameraModel c;
  c.width = 320;
  c.height = 240;
  c.fx = 300.0;
  c.fy = 301.5;
  c.cx = 163.2;
  c.cy = 118.9;
  c.alpha_c = alpha_c;
  c.kc = Distortion::plumb_bob(-0.3, 0.0, 0.001, -0.0005, 0.0);
  return c;
}

// Intensity-weighted centroid of a grey image inside a window.
Eigen::Vector2d centroid(const cv::Mat& grey, const Eigen::Vector2d& around, int radius) {
  double sum = 0, su = 0, sv = 0;
  for (int v = static_cast<int>(around.y()) - radius; v <= around.y() + radius; ++v) {
    for (int u = static_cast<int>(around.x()) - radius; u <= around.x() + radius; ++u) {
      const double w = grey.at<float>(v, u);
      sum += w;
      su += w * u;
      sv += w * v;
    }
  }
  return {su / sum, sv / sum};
}

// A smooth blob (exactly band-limited enough for a sub-0.01 px centroid) at `centre`.
cv::Mat blob_image(int width, int height, const Eigen::Vector2d& centre, double sigma) {
  cv::Mat image(height, width, CV_32F);
  for (int v = 0; v < height; ++v) {
    for (int u = 0; u < width; ++u) {
      const double d2 = std::pow(u - centre.x(), 2) + std::pow(v - centre.y(), 2);
      image.at<float>(v, u) = static_cast<float>(std::exp(-d2 / (2 * sigma * sigma)));
    }
  }
  return image;
}

TEST(DistortionMaps, UndistortMapsPointAtTheRawPositionOfEachRay) {
  for (double alpha_c : {0.0, 0.02}) {  // OpenCV's path and telear's own (skew)
    const CameraModel c = lens_camera(alpha_c);
    const UndistortMaps maps = compute_undistort_maps(c);
    ASSERT_EQ(maps.map_x.type(), CV_32FC1);
    ASSERT_EQ(maps.map_x.size(), cv::Size(320, 240));
    double worst = 0.0;
    for (int v = 0; v < c.height; v += 7) {
      for (int u = 0; u < c.width; u += 5) {
        const Eigen::Vector2d raw =
            c.pixel_from_normalized(c.distort(c.normalized_from_pixel({u, v})));
        worst = std::max(worst, std::hypot(maps.map_x.at<float>(v, u) - raw.x(),
                                           maps.map_y.at<float>(v, u) - raw.y()));
      }
    }
    EXPECT_LT(worst, 1e-3) << "alpha_c " << alpha_c;
  }
}

// The undistorted mode for the wide-angle models: a rational_polynomial lens goes through
// OpenCV's map, an equidistant (fisheye) one through telear's own loop; both must show a point
// where the pinhole with the same K puts it, and the raw-to-pinhole table must invert them.
TEST(DistortionMaps, RationalAndEquidistantLensesUndistortToThePinhole) {
  CameraModel rational = lens_camera();
  rational.kc =
      *Distortion::from_coefficients(DistortionModel::rational_polynomial,
                                     {0.42, -0.08, 0.0009, -0.0006, 0.01, 0.75, 0.02, 0.003});
  CameraModel fisheye = lens_camera();
  fisheye.fx = fisheye.fy = 150.0;
  fisheye.kc =
      *Distortion::from_coefficients(DistortionModel::equidistant, {-0.012, 0.031, -0.018, 0.004});
  for (const CameraModel& c : {rational, fisheye}) {
    SCOPED_TRACE(distortion_model_name(c.kc.model));
    const Eigen::Vector3d p_cam(0.3, -0.2, 1.0);
    const Eigen::Vector2d raw_uv = *c.project(p_cam);
    const Eigen::Vector2d pinhole_uv = *c.project_pinhole(p_cam);
    ASSERT_GT((raw_uv - pinhole_uv).norm(), 2.0);  // the lens moves the point visibly
    const UndistortMaps maps = compute_undistort_maps(c);
    const cv::Mat raw = blob_image(c.width, c.height, raw_uv, 2.0);
    const cv::Mat undistorted = undistort_image(raw, maps);
    EXPECT_LT((centroid(undistorted, pinhole_uv, 10) - pinhole_uv).norm(), 0.1);
    const RawToPinholeLut lut = compute_raw_to_pinhole_lut(c);
    // The table's pinhole position of a raw pixel, distorted again, is that raw pixel.
    const Eigen::Vector2d q(std::lround(raw_uv.x()), std::lround(raw_uv.y()));
    const cv::Vec2f p =
        lut.pinhole_uv.at<cv::Vec2f>(static_cast<int>(q.y()), static_cast<int>(q.x()));
    const Eigen::Vector2d again =
        c.pixel_from_normalized(c.distort(c.normalized_from_pixel({p[0], p[1]})));
    EXPECT_LT((again - q).norm(), 1e-3);
  }
}

TEST(DistortionMaps, UndistortedImageShowsAPointWhereThePinholePutsIt) {
  const CameraModel c = lens_camera();
  const Eigen::Vector3d p_cam(0.35, -0.25, 1.0);
  const Eigen::Vector2d raw_uv = *c.project(p_cam);
  const Eigen::Vector2d pinhole_uv = *c.project_pinhole(p_cam);
  ASSERT_GT((raw_uv - pinhole_uv).norm(), 5.0);  // the distortion is not negligible here
  const cv::Mat raw = blob_image(c.width, c.height, raw_uv, 2.0);
  const cv::Mat undistorted = undistort_image(raw, compute_undistort_maps(c));
  // cv::remap interpolates with 1/32-pixel fixed-point weights: a few hundredths of a pixel.
  EXPECT_LT((centroid(undistorted, pinhole_uv, 10) - pinhole_uv).norm(), 0.05);
}

TEST(DistortionMaps, FoldedRaysHaveNoSourcePixel) {
  CameraModel c = lens_camera();
  c.fx = c.fy = 120.0;  // wide: the image corners lie beyond r = 1.054
  const UndistortMaps maps = compute_undistort_maps(c);
  EXPECT_EQ(maps.map_x.at<float>(0, 0), -1.0f);
  EXPECT_GE(maps.map_x.at<float>(120, 160), 0.0f);
}

TEST(DistortionMaps, RawToPinholeLutInvertsTheDistortion) {
  const CameraModel c = lens_camera(0.01);
  const RawToPinholeLut lut = compute_raw_to_pinhole_lut(c);
  ASSERT_EQ(lut.pinhole_uv.type(), CV_32FC2);
  EXPECT_EQ(lut.invalid_count, 0);
  double worst = 0.0;
  for (int v = 0; v < c.height; ++v) {
    for (int u = 0; u < c.width; ++u) {
      const cv::Vec2f p = lut.pinhole_uv.at<cv::Vec2f>(v, u);
      const Eigen::Vector2d back =
          c.pixel_from_normalized(c.distort(c.normalized_from_pixel({p[0], p[1]})));
      worst = std::max(worst, (back - Eigen::Vector2d(u, v)).norm());
    }
  }
  EXPECT_LT(worst, 1e-3);  // float storage: ~3e-5 px relative
  // Barrel distortion: the raw image's corners see rays beyond the pinhole image.
  EXPECT_LT(lut.min_u, -0.5);
  EXPECT_LT(lut.min_v, -0.5);
  EXPECT_GT(lut.max_u, c.width - 0.5);
  EXPECT_GT(lut.max_v, c.height - 0.5);
}

TEST(DistortionMaps, LutMarksPixelsWithNoRay) {
  CameraModel c = lens_camera();
  c.fx = c.fy = 120.0;
  const RawToPinholeLut lut = compute_raw_to_pinhole_lut(c);
  EXPECT_GT(lut.invalid_count, 0);
  EXPECT_TRUE(std::isnan(lut.pinhole_uv.at<cv::Vec2f>(0, 0)[0]));
  EXPECT_FALSE(std::isnan(lut.pinhole_uv.at<cv::Vec2f>(120, 160)[0]));
}

}  // namespace
}  // namespace telear::vision
