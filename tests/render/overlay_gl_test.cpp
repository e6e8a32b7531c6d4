// The overlay on a headless EGL context: the rendered joint origins of the PUMA 560 land
// where cv::projectPoints puts them, without and with lens distortion, in both modes.
//
// Markers (telear/render/point_markers.hpp) are drawn at the joint origins through the overlay's
// scene callback, one marker per render, and located in the read-back image by their
// intensity-weighted centroid. Expected pixels come from cv::projectPoints (not from telear's
// camera model): with the distortion in raw mode, without it in undistorted mode (the
// undistorted image is an ideal pinhole image with the same K); a second test shows the
// remapped video puts the distorted projection of the same point on that very pixel.

#include "telear/render/overlay.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <opencv2/calib3d.hpp>
#include <random>

#include "gl_test_util.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/pose.hpp"
#include "telear/render/arm_renderer.hpp"
#include "telear/render/point_markers.hpp"
#include "telear/vision/camera_file.hpp"
#include "test_util/test_util.hpp"

namespace telear::render {
namespace {

using test::GlTest;

constexpr float kMarkerRadius = 4.0f;

struct Stats {
  double max_px = 0.0;
  double sum_sq = 0.0;
  int count = 0;
  void add(double e) {
    max_px = std::max(max_px, e);
    sum_sq += e * e;
    ++count;
  }
  double rms() const { return count ? std::sqrt(sum_sq / count) : 0.0; }
};

// cv::projectPoints of base-frame points through `camera` (its distortion or none).
std::vector<Eigen::Vector2d> opencv_project(const vision::CameraModel& camera,
                                            const std::vector<Eigen::Vector3d>& points,
                                            bool with_distortion) {
  std::vector<cv::Point3d> object;
  for (const Eigen::Vector3d& p : points) object.emplace_back(p.x(), p.y(), p.z());
  const Eigen::Vector3d r = core::rotation_vector(camera.T_cam_base.linear());
  const Eigen::Vector3d t = camera.T_cam_base.translation();
  const std::vector<double> kc = camera.kc.coefficients();
  std::vector<cv::Point2d> image;
  cv::projectPoints(object, cv::Vec3d(r.x(), r.y(), r.z()), cv::Vec3d(t.x(), t.y(), t.z()),
                    cv::Matx33d(camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1),
                    with_distortion ? cv::Mat(1, static_cast<int>(kc.size()), CV_64F,
                                              const_cast<double*>(kc.data()))
                                    : cv::Mat(),
                    image);
  std::vector<Eigen::Vector2d> out;
  for (const cv::Point2d& p : image) out.emplace_back(p.x, p.y);
  return out;
}

// Joint origins (frames 0..n and the tool) of the PUMA at several configurations, without
// coincident ones (the wrist frames share an origin).
std::vector<Eigen::Vector3d> joint_origins(const core::RobotModel& model) {
  std::vector<Eigen::VectorXd> configurations;
  for (const char* name : {"qz", "qr", "qn"})
    configurations.push_back(*model.named_configuration(name));
  std::mt19937_64 rng(5);
  for (int i = 0; i < 2; ++i)
    configurations.push_back(telear::test::random_configuration(model, rng));
  std::vector<Eigen::Vector3d> points;
  core::KinematicsData data(model);
  for (const Eigen::VectorXd& q : configurations) {
    core::forward_kinematics(model, data, q);
    std::vector<Eigen::Vector3d> frame_points;
    for (const Eigen::Isometry3d& T : data.T_base_link) frame_points.push_back(T.translation());
    frame_points.push_back(data.T_base_tool.translation() +
                           data.T_base_tool.linear() * Eigen::Vector3d(0, 0, 0.1));
    for (const Eigen::Vector3d& p : frame_points) {
      bool seen = false;
      for (const Eigen::Vector3d& s : points) seen = seen || (s - p).norm() < 1e-3;
      if (!seen) points.push_back(p);
    }
  }
  return points;
}

// Intensity-weighted centroid (red channel) of the pixels within `radius` of `around`.
std::optional<Eigen::Vector2d> centroid(const core::Image& image, const Eigen::Vector2d& around,
                                        int radius) {
  double sum = 0, su = 0, sv = 0;
  const int u0 = static_cast<int>(std::lround(around.x())),
            v0 = static_cast<int>(std::lround(around.y()));
  for (int v = v0 - radius; v <= v0 + radius; ++v) {
    for (int u = u0 - radius; u <= u0 + radius; ++u) {
      if (u < 0 || v < 0 || u >= image.width || v >= image.height) return std::nullopt;
      const double w = image.at(u, v, 0);
      sum += w;
      su += w * u;
      sv += w * v;
    }
  }
  if (sum <= 0) return std::nullopt;
  return Eigen::Vector2d(su / sum, sv / sum);
}

class OverlayTest : public GlTest {
 protected:
  void SetUp() override {
    GlTest::SetUp();
    if (HasFatalFailure()) return;
    model = telear::test::puma560();
    ASSERT_TRUE(model);
    auto rig = vision::load_camera_file(telear::test::data_path("cameras/puma560_stereo.yaml"));
    ASSERT_TRUE(rig) << rig.error().message;
    shipped = rig->left;
    auto m = PointMarkers::create();
    ASSERT_TRUE(m) << m.error().message;
    markers = std::move(m.value());
    auto t = OffscreenTarget::create(shipped.width, shipped.height);
    ASSERT_TRUE(t) << t.error().message;
    target = std::move(t.value());
  }

  // The cameras of the test: an ideal lens, k1 = -0.3 alone, the shipped rig's lens.
  std::vector<std::pair<std::string, vision::CameraModel>> cameras() const {
    vision::CameraModel pinhole = shipped;
    pinhole.kc = {};
    vision::CameraModel barrel = shipped;
    barrel.kc = vision::Distortion::plumb_bob(-0.3, 0, 0, 0, 0);
    return {{"no distortion", pinhole}, {"k1 = -0.3", barrel}, {"shipped rig", shipped}};
  }

  // Renders each point alone as a marker and compares its centroid with cv::projectPoints
  // (or, for a camera with skew, which OpenCV cannot express, with telear's camera model).
  Stats measure(const vision::CameraModel& camera, OverlayMode mode, const std::string& label) {
    auto overlay = Overlay::create(camera, {.mode = mode});
    EXPECT_TRUE(overlay) << overlay.error().message;
    if (!overlay) return {};
    const std::vector<Eigen::Vector3d> points = joint_origins(*model);
    std::vector<Eigen::Vector2d> expected;
    if (camera.alpha_c == 0.0) {
      expected = opencv_project(camera, points, mode == OverlayMode::kRaw);
    } else {
      for (const Eigen::Vector3d& p : points) {
        expected.push_back(mode == OverlayMode::kRaw ? *camera.project(p)
                                                     : *camera.project_pinhole(p));
      }
    }
    Stats stats;
    const int window = static_cast<int>(kMarkerRadius) + 4;
    for (size_t i = 0; i < points.size(); ++i) {
      const Eigen::Vector2d& e = expected[i];
      if (e.x() < 2 * window || e.y() < 2 * window || e.x() > camera.width - 2 * window ||
          e.y() > camera.height - 2 * window) {
        continue;  // out of view
      }
      const Eigen::Vector3f p = points[i].cast<float>();
      overlay->render(target, [&](const Eigen::Matrix4f& projection, const Eigen::Matrix4f& view) {
        markers.draw(projection, view, {p}, kMarkerRadius, Eigen::Vector3f::Ones());
      });
      const std::optional<Eigen::Vector2d> c = centroid(target.read_rgb(), e, window);
      EXPECT_TRUE(c) << label << ": marker " << i << " not found near " << e.transpose();
      if (!c) continue;
      const double error = (*c - e).norm();
      EXPECT_LT(error, 0.1) << label << ": point " << i << " expected at " << e.transpose()
                            << ", rendered at " << c->transpose();
      stats.add(error);
    }
    EXPECT_GE(stats.count, 12) << label << ": too few joint origins in view";
    std::printf("[ projection ] %-28s %2d points  max %.4f px  rms %.4f px\n", label.c_str(),
                stats.count, stats.max_px, stats.rms());
    RecordProperty(label + " max_px", std::to_string(stats.max_px));
    return stats;
  }

  core::RobotModelPtr model;
  vision::CameraModel shipped;
  PointMarkers markers;
  OffscreenTarget target;
};

TEST_F(OverlayTest, JointOriginsLandWhereOpenCvProjectsThemInRawMode) {
  for (const auto& [name, camera] : cameras()) {
    measure(camera, OverlayMode::kRaw, "raw, " + name);
  }
}

TEST_F(OverlayTest, JointOriginsLandWhereOpenCvProjectsThemInUndistortedMode) {
  for (const auto& [name, camera] : cameras()) {
    measure(camera, OverlayMode::kUndistorted, "undistorted, " + name);
  }
}

// Skew (Bouguet's alpha_c) goes through the projection, the undistort maps (telear's own,
// since OpenCV ignores K(0,1)) and the raw look-up table alike.
TEST_F(OverlayTest, SkewedCameraInBothModes) {
  vision::CameraModel camera = shipped;
  camera.alpha_c = 0.01;
  measure(camera, OverlayMode::kRaw, "raw, shipped rig + skew");
  measure(camera, OverlayMode::kUndistorted, "undistorted, shipped rig + skew");
}

// The undistorted mode's two halves agree: a feature of the raw video at the distorted
// projection of a point is remapped onto the pixel where the arm's point is drawn.
TEST_F(OverlayTest, UndistortedVideoPutsTheRawFeatureUnderTheRenderedPoint) {
  vision::CameraModel camera = shipped;
  camera.kc = vision::Distortion::plumb_bob(-0.3, 0, 0, 0, 0);
  auto overlay = Overlay::create(camera, {.mode = OverlayMode::kUndistorted});
  ASSERT_TRUE(overlay) << overlay.error().message;
  const std::vector<Eigen::Vector3d> points = joint_origins(*model);
  const std::vector<Eigen::Vector2d> raw = opencv_project(camera, points, true);
  const std::vector<Eigen::Vector2d> pinhole = opencv_project(camera, points, false);
  int checked = 0;
  double worst = 0.0;
  for (size_t i = 0; i < points.size(); ++i) {
    if (pinhole[i].x() < 20 || pinhole[i].y() < 20 || pinhole[i].x() > camera.width - 20 ||
        pinhole[i].y() > camera.height - 20) {
      continue;
    }
    // A raw frame with one smooth blob (sigma 2 px) at the distorted projection.
    cv::Mat frame(camera.height, camera.width, CV_8UC3, cv::Scalar::all(0));
    for (int v = 0; v < camera.height; ++v) {
      for (int u = 0; u < camera.width; ++u) {
        const double d2 = std::pow(u - raw[i].x(), 2) + std::pow(v - raw[i].y(), 2);
        frame.at<cv::Vec3b>(v, u) =
            cv::Vec3b::all(static_cast<unsigned char>(std::lround(255.0 * std::exp(-d2 / 8.0))));
      }
    }
    overlay->upload_frame(frame.data, ChannelOrder::kBgr);
    overlay->render(target, nullptr);
    const std::optional<Eigen::Vector2d> c = centroid(target.read_rgb(), pinhole[i], 10);
    ASSERT_TRUE(c);
    worst = std::max(worst, (*c - pinhole[i]).norm());
    ++checked;
  }
  EXPECT_GE(checked, 12);
  EXPECT_LT(worst, 0.1);
  std::printf("[ projection ] undistorted video feature vs rendered point: max %.4f px\n", worst);
}

TEST_F(OverlayTest, RawModeShowsTheFrameUnchangedAndSwapsBgr) {
  auto overlay = Overlay::create(shipped, {.mode = OverlayMode::kRaw});
  ASSERT_TRUE(overlay) << overlay.error().message;
  std::vector<std::uint8_t> frame(static_cast<size_t>(shipped.width) * shipped.height * 3);
  std::mt19937 rng(3);
  for (std::uint8_t& b : frame) b = static_cast<std::uint8_t>(rng() & 0xff);
  overlay->upload_frame(frame.data(), ChannelOrder::kRgb);
  overlay->render(target, nullptr);
  EXPECT_EQ(target.read_rgb().pixels, frame);
  overlay->upload_frame(frame.data(), ChannelOrder::kBgr);
  overlay->render(target, nullptr);
  const core::Image bgr = target.read_rgb();
  EXPECT_EQ(bgr.at(10, 20, 0), frame[(20 * shipped.width + 10) * 3 + 2]);
  EXPECT_EQ(bgr.at(10, 20, 2), frame[(20 * shipped.width + 10) * 3 + 0]);
}

// Without distortion the two modes are the same picture: the raw mode's warp is then the
// identity at texel centres. The arm is D1's ArmRenderer, as `telear render` draws it.
TEST_F(OverlayTest, WithoutDistortionBothModesDrawTheSameArm) {
  vision::CameraModel camera = shipped;
  camera.kc = {};
  const core::ArmBody body = core::build_arm_body(*core::body_description_for(*model));
  core::ArmBodyPose pose(*model, body);
  pose.set_configuration(*model->named_configuration("qn"));
  auto arm = ArmRenderer::create(body);
  ASSERT_TRUE(arm) << arm.error().message;
  arm->update(pose);
  std::vector<core::Image> pictures;
  for (OverlayMode mode : {OverlayMode::kUndistorted, OverlayMode::kRaw}) {
    for (float alpha : {1.0f, 0.6f}) {
      auto overlay = Overlay::create(camera, {.mode = mode, .clear_colour = {0.2f, 0.3f, 0.4f}});
      ASSERT_TRUE(overlay) << overlay.error().message;
      overlay->render(target, [&](const Eigen::Matrix4f& projection, const Eigen::Matrix4f& view) {
        DrawOptions options;
        options.alpha = alpha;
        arm->draw(projection, view, options);
      });
      pictures.push_back(target.read_rgb());
    }
  }
  ASSERT_GT(test::count_covered(pictures[0], {51, 77, 102}), 5000);  // the arm is in view
  for (int k = 0; k < 2; ++k) {
    const core::Image& a = pictures[static_cast<size_t>(k)];
    const core::Image& b = pictures[static_cast<size_t>(k + 2)];
    int max_diff = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
      max_diff = std::max(max_diff, std::abs(int(a.pixels[i]) - int(b.pixels[i])));
    }
    EXPECT_LE(max_diff, 2) << (k == 0 ? "opaque" : "ghost");
  }
}

TEST_F(OverlayTest, InvalidCameraIsAnError) {
  vision::CameraModel camera = shipped;
  camera.fx = 0.0;
  auto overlay = Overlay::create(camera);
  ASSERT_FALSE(overlay);
  EXPECT_EQ(overlay.error().message,
            "overlay: fx (camera_matrix[0][0]) must be positive and finite, got 0");
}

}  // namespace
}  // namespace telear::render
