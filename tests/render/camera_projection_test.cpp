// Pure math, no GL context: the GL projection built from K puts points exactly where
// cv::projectPoints puts them (no distortion: distortion is not projective and is the
// overlay's job, tested in overlay_gl_test.cpp).

#include "telear/render/camera_projection.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <opencv2/calib3d.hpp>
#include <random>

#include "telear/core/pose.hpp"

namespace telear::render {
namespace {

vision::CameraModel camera() {
  vision::CameraModel c;
  c.width = 640;
  c.height = 480;
  c.fx = 812.5;
  c.fy = 797.25;
  c.cx = 301.7;  // far from the centre: the principal point matters
  c.cy = 255.2;
  c.T_cam_base = core::pose_from_xyz_rpy({0.1, -0.2, 1.5}, {2.1, 0.1, -0.3});
  return c;
}

std::vector<cv::Point2d> opencv_project(const vision::CameraModel& c,
                                        const std::vector<Eigen::Vector3d>& points) {
  std::vector<cv::Point3d> object;
  for (const Eigen::Vector3d& p : points) object.emplace_back(p.x(), p.y(), p.z());
  const Eigen::Vector3d r = core::rotation_vector(c.T_cam_base.linear());
  const Eigen::Vector3d t = c.T_cam_base.translation();
  std::vector<cv::Point2d> out;
  cv::projectPoints(object, cv::Vec3d(r.x(), r.y(), r.z()), cv::Vec3d(t.x(), t.y(), t.z()),
                    cv::Matx33d(c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1), cv::noArray(), out);
  return out;
}

std::vector<Eigen::Vector3d> points_in_front(const vision::CameraModel& c, int count) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> lateral(-0.6, 0.6), depth(0.2, 30.0);
  std::vector<Eigen::Vector3d> points;
  const Eigen::Isometry3d T_base_cam = c.T_cam_base.inverse();
  for (int i = 0; i < count; ++i) {
    const double z = depth(rng);
    points.push_back(T_base_cam * Eigen::Vector3d(lateral(rng) * z, lateral(rng) * z, z));
  }
  return points;
}

TEST(CameraProjection, GlPipelineMatchesOpenCvProjectPointsTo1e9Pixels) {
  const vision::CameraModel c = camera();
  const PinholeProjection projection = PinholeProjection::from_camera(c, 0.1, 100.0);
  const std::vector<Eigen::Vector3d> points = points_in_front(c, 2000);
  const std::vector<cv::Point2d> expected = opencv_project(c, points);
  double worst = 0.0;
  for (size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d uv = pixel_of_point(projection, c.T_cam_base, points[i]);
    worst = std::max(worst, (uv - Eigen::Vector2d(expected[i].x, expected[i].y)).norm());
  }
  EXPECT_LT(worst, 1e-9);
  std::printf("[ projection ] GL matrices vs cv::projectPoints, 2000 points: max %.2e px\n", worst);
}

TEST(CameraProjection, PixelCentresAndImageEdgesFollowOpenCvConvention) {
  vision::CameraModel c = camera();
  c.T_cam_base = Eigen::Isometry3d::Identity();
  const Eigen::Matrix4d P = gl_projection(PinholeProjection::from_camera(c));
  auto ndc = [&](double u, double v) {
    // The ray through OpenCV pixel (u, v) at depth 2 m.
    const Eigen::Vector4d p((u - c.cx) / c.fx * 2.0, (v - c.cy) / c.fy * 2.0, 2.0, 1.0);
    const Eigen::Vector4d clip = P * p;
    return Eigen::Vector2d(clip.x() / clip.w(), clip.y() / clip.w());
  };
  // The image's outer edges (-0.5 and W - 0.5) are NDC -1 and +1; row 0 is at the top.
  EXPECT_NEAR(ndc(-0.5, -0.5).x(), -1.0, 1e-12);
  EXPECT_NEAR(ndc(-0.5, -0.5).y(), 1.0, 1e-12);
  EXPECT_NEAR(ndc(639.5, 479.5).x(), 1.0, 1e-12);
  EXPECT_NEAR(ndc(639.5, 479.5).y(), -1.0, 1e-12);
  // Pixel (0, 0)'s centre is GL window position (0.5, H - 0.5).
  EXPECT_EQ(window_from_pixel({0.0, 0.0}, 480), Eigen::Vector2d(0.5, 479.5));
  EXPECT_EQ(pixel_from_window({0.5, 479.5}, 480), Eigen::Vector2d(0.0, 0.0));
}

TEST(CameraProjection, DepthMapsNearAndFarToMinusOneAndOne) {
  const PinholeProjection projection = PinholeProjection::from_camera(camera(), 0.25, 12.0);
  const Eigen::Matrix4d P = gl_projection(projection);
  for (double z : {0.25, 12.0}) {
    const Eigen::Vector4d clip = P * Eigen::Vector4d(0.1 * z, -0.05 * z, z, 1.0);
    EXPECT_NEAR(clip.z() / clip.w(), z == 0.25 ? -1.0 : 1.0, 1e-12);
    EXPECT_DOUBLE_EQ(clip.w(), z);
  }
}

TEST(CameraProjection, SkewIsHonoured) {
  vision::CameraModel c = camera();
  c.alpha_c = 0.02;
  const PinholeProjection projection = PinholeProjection::from_camera(c);
  EXPECT_DOUBLE_EQ(projection.skew, 0.02 * c.fx);
  for (const Eigen::Vector3d& p : points_in_front(c, 200)) {
    const Eigen::Vector2d uv = pixel_of_point(projection, c.T_cam_base, p);
    EXPECT_LT((uv - *c.project_pinhole(p)).norm(), 1e-9);
  }
}

TEST(CameraProjection, RegionShowsTheSamePointsShifted) {
  const vision::CameraModel c = camera();
  const PinholeProjection full = PinholeProjection::from_camera(c);
  // A framebuffer with a margin of 37 px left and 21 px above the image (raw overlay mode).
  const PinholeProjection margin = full.region(-37, -21, 640 + 74, 480 + 42);
  for (const Eigen::Vector3d& p : points_in_front(c, 200)) {
    const Eigen::Vector2d a = pixel_of_point(full, c.T_cam_base, p);
    const Eigen::Vector2d b = pixel_of_point(margin, c.T_cam_base, p);
    EXPECT_LT((b - (a + Eigen::Vector2d(37, 21))).norm(), 1e-9);
  }
}

TEST(CameraProjection, ViewIsTCamBaseAndFovIsDerivedFromK) {
  const vision::CameraModel c = camera();
  EXPECT_EQ(gl_view(c.T_cam_base), c.T_cam_base.matrix());
  const PinholeProjection p = PinholeProjection::from_camera(c);
  EXPECT_NEAR(vertical_fov(p), 2.0 * std::atan(240.0 / 797.25), 1e-15);
  EXPECT_NEAR(horizontal_fov(p), 2.0 * std::atan(320.0 / 812.5), 1e-15);
}

}  // namespace
}  // namespace telear::render
