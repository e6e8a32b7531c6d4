// The URDF mesh arms (ur6, arm7) are drawn where their meshes are: the silhouette telear
// renders through the AR view's raw-mode overlay matches a silhouette built independently with
// OpenCV from the same meshes.
//
// Rendered mask: the arm drawn solid in one colour (white, ambient 1, no diffuse) over black
// by render::Overlay in raw mode (the path that lands the ghost on the distorted video), read
// back and thresholded at half intensity.
//
// Reference mask: every part's vertices (core::ArmBody, the body telear uploads), moved by
// ArmBodyPose::T_base_part, projected with cv::projectPoints (K, distortion, T_cam_base), every
// triangle filled with cv::fillConvexPoly. The fill runs on an 8x finer grid and is averaged
// down (cv::INTER_AREA) and thresholded at half coverage, so a pixel is in the reference when
// about half of it is covered, as GL's centre sampling decides; fillConvexPoly is inclusive
// (it also sets the pixels its edges touch), which at 1x would add a whole boundary row and
// cost a few percent of IoU; at 8x it is 1/16 px per edge (at 4x the IoU measured 0.005 lower).
// With distortion the straight triangle edges between distorted vertices approximate the curved
// edges of the true image; the meshes' triangles are small, so the error stays below a pixel's
// fraction.
//
// Measured on llvmpipe (docs/rendering.md, "Mesh silhouettes"; silhouettes of 15k to 24k
// pixels): IoU 0.994 .. 0.996 without distortion, 0.988 .. 0.991 with it; the threshold is
// 0.97. A control shows that the threshold discriminates: the drawing compared with a
// reference whose joint 2 is turned by 2 degrees scores 0.84 (ur6) and 0.91 (arm7).

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "gl_test_util.hpp"
#include "telear/core/arm_body.hpp"
#include "telear/core/arm_body_pose.hpp"
#include "telear/core/number_format.hpp"
#include "telear/core/pose.hpp"
#include "telear/geometry/robot_assets.hpp"
#include "telear/render/arm_renderer.hpp"
#include "telear/render/overlay.hpp"
#include "telear/vision/camera_model.hpp"
#include "test_util/test_util.hpp"

namespace telear::render {
namespace {

using test::GlTest;

constexpr int kWidth = 640;
constexpr int kHeight = 480;
constexpr int kSupersample = 8;      // reference fill grid: 8 x 8 sub-pixels per pixel
constexpr int kFillShift = 8;        // fillConvexPoly's fractional bits (1/256 px)
constexpr double kMinIou = 0.97;     // the measured values are ~0.99 (header comment)
constexpr int kBorderMargin_px = 4;  // the arm must stay this far from the image border

// The camera of the test: 640 x 480, 45 degrees vertical field of view, in front of the arm
// and to its right, a little above the table, seeing both arms whole at their named
// configurations (the mask-border assertion checks it). Distortion as the shipped rigs'.
vision::CameraModel test_camera(bool with_distortion) {
  vision::CameraModel camera = vision::look_at_camera(
      kWidth, kHeight, 45.0 * std::numbers::pi / 180.0, Eigen::Vector3d(1.3, -0.95, 0.9),
      Eigen::Vector3d(0.25, -0.1, 0.3), Eigen::Vector3d::UnitZ());
  if (with_distortion) camera.kc = vision::Distortion::plumb_bob(-0.28, 0.07, 0.0009, -0.0004, 0.0);
  return camera;
}

// 255 where the pixel belongs to the arm, 0 elsewhere.
cv::Mat mask_from_image(const core::Image& image) {
  cv::Mat mask(image.height, image.width, CV_8U, cv::Scalar(0));
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      if (image.at(x, y, 0) >= 128) mask.at<unsigned char>(y, x) = 255;
    }
  }
  return mask;
}

// The reference silhouette: OpenCV's projection of the body's triangles (header comment).
// `T_base_part` is one matrix per part of `body`.
cv::Mat opencv_silhouette(const core::ArmBody& body,
                          const std::vector<Eigen::Matrix4f>& T_base_part,
                          const vision::CameraModel& camera) {
  const Eigen::Vector3d r = core::rotation_vector(camera.T_cam_base.linear());
  const Eigen::Vector3d t = camera.T_cam_base.translation();
  const cv::Matx33d K(camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1);
  const std::vector<double> kc = camera.kc.coefficients();
  const cv::Mat distortion(1, static_cast<int>(kc.size()), CV_64F, const_cast<double*>(kc.data()));
  cv::Mat fine(kHeight * kSupersample, kWidth * kSupersample, CV_8U, cv::Scalar(0));
  for (int k = 0; k < body.part_count(); ++k) {
    const core::Mesh& mesh = body.parts[static_cast<std::size_t>(k)].mesh;
    if (mesh.triangles.empty()) continue;
    const Eigen::Matrix4d T = T_base_part[static_cast<std::size_t>(k)].cast<double>();
    std::vector<cv::Point3d> object;
    object.reserve(mesh.vertices.size());
    for (const core::MeshVertex& v : mesh.vertices) {
      const Eigen::Vector4d p = T * Eigen::Vector4d(v.position[0], v.position[1], v.position[2], 1);
      object.emplace_back(p.x(), p.y(), p.z());
    }
    std::vector<cv::Point2d> image;
    cv::projectPoints(object, cv::Vec3d(r.x(), r.y(), r.z()), cv::Vec3d(t.x(), t.y(), t.z()), K,
                      distortion, image);
    // Pixel centres are at integers in both grids: fine = s (coarse + 0.5) - 0.5.
    std::vector<cv::Point> fixed(image.size());
    const auto to_fine = [](double coarse) {
      const double fine = (coarse + 0.5) * kSupersample - 0.5;
      return static_cast<int>(std::lround(fine * (1 << kFillShift)));
    };
    for (std::size_t i = 0; i < image.size(); ++i) {
      fixed[i] = cv::Point(to_fine(image[i].x), to_fine(image[i].y));
    }
    for (std::size_t i = 0; i + 2 < mesh.triangles.size(); i += 3) {
      const cv::Point triangle[3] = {fixed[mesh.triangles[i]], fixed[mesh.triangles[i + 1]],
                                     fixed[mesh.triangles[i + 2]]};
      cv::fillConvexPoly(fine, triangle, 3, cv::Scalar(255), cv::LINE_8, kFillShift);
    }
  }
  cv::Mat coarse;
  cv::resize(fine, coarse, cv::Size(kWidth, kHeight), 0, 0, cv::INTER_AREA);
  cv::Mat mask;
  cv::threshold(coarse, mask, 127, 255, cv::THRESH_BINARY);
  return mask;
}

double iou(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat both, either;
  cv::bitwise_and(a, b, both);
  cv::bitwise_or(a, b, either);
  const int u = cv::countNonZero(either);
  return u > 0 ? static_cast<double>(cv::countNonZero(both)) / u : 0.0;
}

// Pixels set in `a` and not in `b`.
int count_only(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat only;
  cv::bitwise_and(a, ~b, only);
  return cv::countNonZero(only);
}

// Covered pixels within `margin` of the image border.
int pixels_near_border(const cv::Mat& mask, int margin) {
  const cv::Rect inner(margin, margin, mask.cols - 2 * margin, mask.rows - 2 * margin);
  return cv::countNonZero(mask) - cv::countNonZero(mask(inner));
}

// A shipped robot file (data/robots/NAME.yaml), meshes from its package as they are (no level
// of detail: the test compares telear's drawing with the files' own triangles).
Result<geometry::RobotAssets> load_shipped(const std::string& robot) {
  core::RobotSpec spec;
  spec.name_or_path = telear::test::data_path("robots/" + robot + ".yaml");
  geometry::GeometryOptions as_loaded;
  as_loaded.visual_tolerance_m = 0.0;
  return geometry::load_robot_assets(spec, as_loaded);
}

struct Pose {
  std::string configuration;
  float gripper_opening_m;
};

class MeshSilhouetteTest : public GlTest {
 protected:
  void SetUp() override {
    GlTest::SetUp();
    if (HasFatalFailure()) return;
    auto t = OffscreenTarget::create(kWidth, kHeight);
    ASSERT_TRUE(t) << t.error().message;
    target = std::move(t.value());
  }

  // Draws the arm through the raw-mode overlay and returns the binary mask.
  cv::Mat telear_silhouette(const ArmRenderer& arm, const vision::CameraModel& camera) {
    auto overlay = Overlay::create(camera, {.mode = OverlayMode::kRaw});
    EXPECT_TRUE(overlay) << overlay.error().message;
    if (!overlay) return {};
    DrawOptions options;
    options.colour = Eigen::Vector3f::Ones();
    options.lighting.ambient = Eigen::Vector3f::Ones();
    options.lighting.diffuse = Eigen::Vector3f::Zero();
    overlay->render(target, [&](const Eigen::Matrix4f& projection, const Eigen::Matrix4f& view) {
      arm.draw(projection, view, options);
    });
    return mask_from_image(target.read_rgb());
  }

  // Renders `robot` at each pose through both cameras and compares with OpenCV.
  void check_robot(const std::string& robot, const std::vector<Pose>& poses) {
    auto assets = load_shipped(robot);
    ASSERT_TRUE(assets) << assets.error().message;
    const core::ArmBody body = core::build_arm_body(assets->body);
    ASSERT_TRUE(body.has_gripper()) << robot;
    ASSERT_GT(body.triangle_count(), 5000u) << robot << ": not the mesh arm";
    auto arm = ArmRenderer::create(body);
    ASSERT_TRUE(arm) << arm.error().message;
    std::vector<cv::Mat> rendered_masks;
    for (const Pose& p : poses) {
      const auto q = assets->model()->named_configuration(p.configuration);
      ASSERT_TRUE(q) << robot << " has no configuration " << p.configuration;
      core::ArmBodyPose pose(*assets->model(), body);
      pose.set_configuration(*q);
      pose.set_gripper_opening(p.gripper_opening_m);
      arm->update(pose);
      for (bool distorted : {false, true}) {
        const vision::CameraModel camera = test_camera(distorted);
        const std::string label = robot + " " + p.configuration + ", opening " +
                                  core::format_fixed(p.gripper_opening_m, 2) +
                                  (distorted ? " m, distorted" : " m, no distortion");
        const cv::Mat rendered = telear_silhouette(*arm, camera);
        ASSERT_FALSE(rendered.empty()) << label;
        const cv::Mat reference = opencv_silhouette(body, pose.T_base_part(), camera);
        // The whole arm is in view: a sizeable silhouette that stays off the border.
        const int area = cv::countNonZero(rendered);
        EXPECT_GT(area, kWidth * kHeight / 50) << label << ": arm too small or missing";
        EXPECT_LT(area, kWidth * kHeight / 3) << label << ": arm fills the view";
        EXPECT_EQ(pixels_near_border(rendered, kBorderMargin_px), 0)
            << label << ": the arm touches the image border (clipped)";
        EXPECT_EQ(pixels_near_border(reference, kBorderMargin_px), 0) << label;
        const double value = iou(rendered, reference);
        EXPECT_GE(value, kMinIou) << label;
        std::printf(
            "[ silhouette ] %-40s %6d px  IoU %.4f  (%d px only drawn, %d only in OpenCV)\n",
            label.c_str(), area, value, count_only(rendered, reference),
            count_only(reference, rendered));
        RecordProperty(label + " IoU", std::to_string(value));
        if (!distorted) rendered_masks.push_back(rendered);

        // Control: the same comparison against a slightly wrong pose (joint 2 + 2 degrees)
        // fails the threshold, so the threshold tells a right drawing from a wrong one.
        if (&p == &poses.front() && !distorted) {
          core::ArmBodyPose off(*assets->model(), body);
          Eigen::VectorXd q_off = *q;
          q_off[1] += 2.0 * std::numbers::pi / 180.0;
          off.set_configuration(q_off);
          off.set_gripper_opening(p.gripper_opening_m);
          const double off_value =
              iou(rendered, opencv_silhouette(body, off.T_base_part(), camera));
          EXPECT_LT(off_value, kMinIou) << label << ": the control pose passes the threshold";
          std::printf("[ silhouette ] %-40s control (joint 2 + 2 deg): IoU %.4f\n", label.c_str(),
                      off_value);
        }
      }
    }
    // The poses are different pictures (the configurations and the opening took effect).
    for (std::size_t i = 1; i < rendered_masks.size(); ++i) {
      EXPECT_LT(iou(rendered_masks[0], rendered_masks[i]), 0.9) << robot;
    }
  }

  OffscreenTarget target;
};

TEST_F(MeshSilhouetteTest, Ur6MatchesOpenCvProjectionOfItsMeshes) {
  check_robot("ur6", {{"home", 0.0f}, {"ready", 0.08f}});
}

TEST_F(MeshSilhouetteTest, Arm7MatchesOpenCvProjectionOfItsMeshes) {
  check_robot("arm7", {{"home", 0.0f}, {"ready", 0.08f}});
}

// The gripper alone: the same configuration with the fingers closed and wide open are
// different silhouettes, each matching its reference (the moving parts move where the
// URDF's mimic joints put them).
TEST_F(MeshSilhouetteTest, GripperOpeningMovesTheFingersWhereTheMeshesSay) {
  auto assets = load_shipped("ur6");
  ASSERT_TRUE(assets) << assets.error().message;
  const core::ArmBody body = core::build_arm_body(assets->body);
  auto arm = ArmRenderer::create(body);
  ASSERT_TRUE(arm) << arm.error().message;
  const vision::CameraModel camera = test_camera(true);
  std::vector<cv::Mat> masks;
  for (float opening : {0.0f, 0.08f}) {
    core::ArmBodyPose pose(*assets->model(), body);
    pose.set_configuration(*assets->model()->named_configuration("home"));
    pose.set_gripper_opening(opening);
    arm->update(pose);
    masks.push_back(telear_silhouette(*arm, camera));
    const double value = iou(masks.back(), opencv_silhouette(body, pose.T_base_part(), camera));
    EXPECT_GE(value, kMinIou) << "opening " << opening;
  }
  cv::Mat changed;
  cv::bitwise_xor(masks[0], masks[1], changed);
  EXPECT_GT(cv::countNonZero(changed), 50) << "the fingers did not move";
}

}  // namespace
}  // namespace telear::render
