#include "telear/vision/camera_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <opencv2/calib3d.hpp>
#include <random>

#include "telear/core/pose.hpp"
#include "telear/vision/opencv_camera.hpp"

namespace telear::vision {
namespace {

CameraModel test_camera() {
  CameraModel c;
  c.width = 640;
  c.height = 480;
  c.fx = 812.5;
  c.fy = 809.25;
  c.cx = 331.7;
  c.cy = 236.2;
  c.kc = Distortion::plumb_bob(-0.3, 0.12, 0.0011, -0.0007, -0.02);
  c.T_cam_base = core::pose_from_xyz_rpy({0.1, -0.2, 1.5}, {2.1, 0.1, -0.3});
  return c;
}

// Random points in front of the camera whose distorted image falls inside the monotonic
// radius (OpenCV and telear both evaluate the polynomial; they agree anywhere).
std::vector<Eigen::Vector3d> random_points_in_view(const CameraModel& c, int count,
                                                   std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-0.45, 0.45), depth(0.3, 4.0);
  std::vector<Eigen::Vector3d> points;
  const Eigen::Isometry3d T_base_cam = c.T_cam_base.inverse();
  for (int i = 0; i < count; ++i) {
    const double z = depth(rng);
    points.push_back(T_base_cam * Eigen::Vector3d(u(rng) * z, u(rng) * z, z));
  }
  return points;
}

TEST(CameraModel, ProjectEqualsOpenCvProjectPointsWithDistortion) {
  const CameraModel c = test_camera();
  std::mt19937_64 rng(7);
  const std::vector<Eigen::Vector3d> points = random_points_in_view(c, 500, rng);
  const std::vector<cv::Point2d> expected = opencv_project(c, points);
  double worst = 0.0;
  for (size_t i = 0; i < points.size(); ++i) {
    const std::optional<Eigen::Vector2d> uv = c.project(points[i]);
    ASSERT_TRUE(uv);
    worst = std::max(worst, (*uv - Eigen::Vector2d(expected[i].x, expected[i].y)).norm());
  }
  EXPECT_LT(worst, 1e-9);
}

TEST(CameraModel, SkewFollowsBouguetWhichOpenCvProjectPointsIgnores) {
  CameraModel c = test_camera();
  c.alpha_c = 0.01;
  const Eigen::Vector3d p_base = c.T_cam_base.inverse() * Eigen::Vector3d(0.2, 0.3, 1.0);
  const Eigen::Vector2d xd = c.distort({0.2, 0.3});
  const Eigen::Vector2d uv = *c.project(p_base);
  EXPECT_NEAR(uv.x(), c.fx * (xd.x() + 0.01 * xd.y()) + c.cx, 1e-9);
  EXPECT_NEAR(uv.y(), c.fy * xd.y() + c.cy, 1e-9);
  EXPECT_DOUBLE_EQ(c.K()(0, 1), 0.01 * c.fx);
  // OpenCV drops K(0,1): its answer is the skew-free one, off by fx * alpha_c * yd pixels.
  const cv::Point2d cv_uv = opencv_project(c, {p_base})[0];
  EXPECT_NEAR(uv.x() - cv_uv.x, c.fx * 0.01 * xd.y(), 1e-9);
  EXPECT_NEAR(uv.y(), cv_uv.y, 1e-9);
  // normalized_from_pixel inverts pixel_from_normalized, skew included.
  EXPECT_LT((c.normalized_from_pixel(uv) - xd).norm(), 1e-14);
}

TEST(CameraModel, UndistortInvertsDistortAndAgreesWithOpenCv) {
  const CameraModel c = test_camera();
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-0.45, 0.45);
  std::vector<cv::Point2d> distorted_pixels;
  std::vector<Eigen::Vector2d> truth;
  for (int i = 0; i < 300; ++i) {
    const Eigen::Vector2d x(u(rng), u(rng));
    const Eigen::Vector2d xd = c.distort(x);
    const std::optional<Eigen::Vector2d> back = c.undistort(xd);
    ASSERT_TRUE(back);
    ASSERT_LT((*back - x).norm(), 1e-13);
    const Eigen::Vector2d uv = c.pixel_from_normalized(xd);
    distorted_pixels.emplace_back(uv.x(), uv.y());
    truth.push_back(x);
  }
  cv::Matx33d K;
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) K(r, k) = c.K()(r, k);
  const std::vector<double> kc = c.kc.coefficients();
  std::vector<cv::Point2d> normalized;
  cv::undistortPoints(
      distorted_pixels, normalized, K,
      cv::Mat(1, static_cast<int>(kc.size()), CV_64F, const_cast<double*>(kc.data())),
      cv::noArray(), cv::noArray(),
      cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 200, 0));
  for (size_t i = 0; i < truth.size(); ++i) {
    EXPECT_LT((Eigen::Vector2d(normalized[i].x, normalized[i].y) - truth[i]).norm(), 1e-9);
  }
}

// A wide-angle lens in the rational model and a fisheye in the equidistant one, with the
// coefficients' typical signs and sizes (cv::calibrateCamera / cv::fisheye::calibrate output).
CameraModel rational_camera() {
  CameraModel c = test_camera();
  c.kc = *Distortion::from_coefficients(DistortionModel::rational_polynomial,
                                        {0.42, -0.08, 0.0009, -0.0006, 0.01, 0.75, 0.02, 0.003});
  return c;
}

CameraModel fisheye_camera() {
  CameraModel c = test_camera();
  c.fx = c.fy = 290.0;
  c.kc =
      *Distortion::from_coefficients(DistortionModel::equidistant, {-0.012, 0.031, -0.018, 0.004});
  return c;
}

TEST(CameraModel, RationalAndEquidistantProjectAsOpenCvDoes) {
  for (const CameraModel& c : {rational_camera(), fisheye_camera()}) {
    SCOPED_TRACE(distortion_model_name(c.kc.model));
    std::mt19937_64 rng(11);
    // Up to 1.2 normalized radius (50 degrees off axis) for both lenses.
    std::uniform_real_distribution<double> u(-0.85, 0.85), depth(0.3, 4.0);
    std::vector<Eigen::Vector3d> points;
    const Eigen::Isometry3d T_base_cam = c.T_cam_base.inverse();
    for (int i = 0; i < 500; ++i) {
      const double z = depth(rng);
      points.push_back(T_base_cam * Eigen::Vector3d(u(rng) * z, u(rng) * z, z));
    }
    const std::vector<cv::Point2d> expected = opencv_project(c, points);
    double worst = 0.0;
    for (size_t i = 0; i < points.size(); ++i) {
      const std::optional<Eigen::Vector2d> uv = c.project(points[i]);
      ASSERT_TRUE(uv);
      worst = std::max(worst, (*uv - Eigen::Vector2d(expected[i].x, expected[i].y)).norm());
    }
    EXPECT_LT(worst, 1e-8);
  }
}

TEST(CameraModel, RationalAndEquidistantUndistortInvertDistort) {
  for (const CameraModel& c : {rational_camera(), fisheye_camera()}) {
    SCOPED_TRACE(distortion_model_name(c.kc.model));
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-1.5, 1.5);
    double worst = 0.0;
    for (int i = 0; i < 300; ++i) {
      const Eigen::Vector2d x(u(rng), u(rng));
      const std::optional<Eigen::Vector2d> back = c.undistort(c.distort(x));
      ASSERT_TRUE(back) << x.transpose();
      worst = std::max(worst, (*back - x).norm());
    }
    EXPECT_LT(worst, 1e-12);
  }
  // The centre maps to itself (theta_d / r -> 1) and a fisheye's 80-degree ray comes back too.
  const CameraModel fisheye = fisheye_camera();
  EXPECT_EQ(fisheye.distort({0.0, 0.0}), Eigen::Vector2d(0.0, 0.0));
  const Eigen::Vector2d far(std::tan(80.0 * std::numbers::pi / 180.0), 0.0);
  EXPECT_LT((*fisheye.undistort(fisheye.distort(far)) - far).norm(), 1e-9);
}

TEST(CameraModel, EquidistantMonotonicRadiusIsWhereThetaDStopsGrowing) {
  CameraModel c = fisheye_camera();
  EXPECT_TRUE(std::isinf(c.max_monotonic_radius()));
  // theta_d = theta (1 - 0.2 theta^2): d/dtheta = 1 - 0.6 theta^2 = 0 at theta = 1.2910.
  c.kc = *Distortion::from_coefficients(DistortionModel::equidistant, {-0.2, 0.0, 0.0, 0.0});
  EXPECT_NEAR(c.max_monotonic_radius(), std::tan(std::sqrt(1.0 / 0.6)), 1e-6);
  EXPECT_FALSE(c.undistort_within({3.0, 0.0}, c.max_monotonic_radius()));
}

TEST(CameraModel, DistortionModelsHaveTheirRosNamesAndCoefficientCounts) {
  EXPECT_STREQ(distortion_model_name(DistortionModel::rational_polynomial), "rational_polynomial");
  EXPECT_EQ(*parse_distortion_model("fisheye"), DistortionModel::equidistant);
  EXPECT_EQ(parse_distortion_model("kannala_brandt").error().message,
            "unknown distortion model 'kannala_brandt' (expected plumb_bob, rational_polynomial "
            "or equidistant)");
  EXPECT_EQ(rational_camera().kc.coefficients().size(), 8u);
  EXPECT_EQ(fisheye_camera().kc.coefficients(),
            (std::vector<double>{-0.012, 0.031, -0.018, 0.004}));
  EXPECT_EQ(Distortion::from_coefficients(DistortionModel::equidistant, {0.1, 0.2, 0.0, 0.0, 0.0})
                .error()
                .message,
            "equidistant takes 4 distortion coefficients, got 5");
  // A short plumb_bob vector (k1, k2, p1, p2) reads k3 = 0, as OpenCV and ROS do.
  EXPECT_EQ(Distortion::from_coefficients(DistortionModel::plumb_bob, {0.1, 0.2, 0.0, 0.0})->k3,
            0.0);
  CameraModel bad = rational_camera();
  bad.kc.k5 = std::nan("");
  EXPECT_EQ(validate_camera(bad).error().message, "distortion_coefficients: k5 must be finite");
}

TEST(CameraModel, MonotonicRadiusOfPureBarrelDistortion) {
  CameraModel c = test_camera();
  c.kc = Distortion::plumb_bob(-0.3, 0, 0, 0, 0);
  // d/dr (r - 0.3 r^3) = 1 - 0.9 r^2 = 0 at r = 1 / sqrt(0.9).
  EXPECT_NEAR(c.max_monotonic_radius(), 1.0 / std::sqrt(0.9), 1e-9);
  // The largest distorted radius is 1.054 - 0.3 * 1.054^3 = 0.7027: beyond it no ray exists.
  EXPECT_FALSE(c.undistort({0.75, 0.0}));
  EXPECT_TRUE(c.undistort({0.65, 0.0}));
  c.kc = {};
  EXPECT_TRUE(std::isinf(c.max_monotonic_radius()));
  EXPECT_EQ(*c.undistort({3.0, -2.0}), Eigen::Vector2d(3.0, -2.0));
}

TEST(CameraModel, BehindTheCameraIsNotProjected) {
  const CameraModel c = test_camera();
  const Eigen::Isometry3d T_base_cam = c.T_cam_base.inverse();
  EXPECT_FALSE(c.project(T_base_cam * Eigen::Vector3d(0.1, 0.1, -1.0)));
  EXPECT_FALSE(c.project_pinhole(T_base_cam * Eigen::Vector3d(0.1, 0.1, 0.0)));
}

TEST(CameraModel, ValidateNamesTheField) {
  CameraModel c = test_camera();
  EXPECT_TRUE(validate_camera(c).ok());
  c.fx = -1.0;
  EXPECT_EQ(validate_camera(c).error().message,
            "fx (camera_matrix[0][0]) must be positive and finite, got -1");
  c = test_camera();
  c.width = 0;
  EXPECT_EQ(validate_camera(c).error().message, "image_width must be in [1, 16384], got 0");
  c = test_camera();
  c.kc.p2 = NAN;
  EXPECT_EQ(validate_camera(c).error().message, "distortion_coefficients: p2 must be finite");
  c = test_camera();
  c.T_cam_base.matrix()(0, 0) = 2.0;
  EXPECT_NE(validate_camera(c).error().message.find("T_cam_base must be a rigid transform"),
            std::string::npos);
}

TEST(CameraModel, LookAtPutsTheTargetAtTheImageCentreWithUpUp) {
  const CameraModel c =
      look_at_camera(640, 480, 1.0, {2.0, -1.0, 1.5}, {0.0, 0.0, 0.5}, Eigen::Vector3d::UnitZ());
  EXPECT_TRUE(validate_camera(c).ok());
  const Eigen::Vector2d centre = *c.project({0.0, 0.0, 0.5});
  EXPECT_NEAR(centre.x(), 319.5, 1e-9);
  EXPECT_NEAR(centre.y(), 239.5, 1e-9);
  EXPECT_LT(c.project({0.0, 0.0, 0.8})->y(), centre.y());  // higher in the world: up in image
  EXPECT_NEAR(c.fy, 240.0 / std::tan(0.5), 1e-9);
}

TEST(CameraModel, AResizedCameraSeesEveryPointWhereTheScaledImageHasIt) {
  CameraModel c = test_camera();
  c.alpha_c = 0.002;
  const CameraModel half = resized_camera(c, c.width / 2, c.height / 2);
  EXPECT_EQ(half.width, c.width / 2);
  for (const Eigen::Vector3d& p :
       {Eigen::Vector3d(0.1, -0.05, 1.0), Eigen::Vector3d(-0.3, 0.2, 2.0)}) {
    const Eigen::Vector2d full_px = *c.project(c.T_cam_base.inverse() * p);
    const Eigen::Vector2d half_px = *half.project(c.T_cam_base.inverse() * p);
    // Pixel centres: full pixel u covers half-image [u / 2, (u + 1) / 2).
    EXPECT_NEAR(half_px.x(), 0.5 * (full_px.x() + 0.5) - 0.5, 1e-9);
    EXPECT_NEAR(half_px.y(), 0.5 * (full_px.y() + 0.5) - 0.5, 1e-9);
  }
}

}  // namespace
}  // namespace telear::vision
