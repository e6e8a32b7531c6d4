// ChArUco calibration against the simulator's ground truth: views of a ChArUco board rendered
// through the TRUE cameras of the PUMA rig (their distortion included, 1 grey level of noise),
// whole and partly out of frame, written as PNG files and taken through telear's image
// detection and calibration (what `telear calibrate --pattern charuco:...` runs).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <iostream>

#include "telear/sim/calibration_targets.hpp"
#include "telear/sim/stereo_rig.hpp"
#include "telear/vision/calibration_images.hpp"
#include "telear/vision/calibration_pattern.hpp"
#include "telear/vision/image_file.hpp"
#include "telear/vision/mono_calibration.hpp"
#include "telear/vision/stereo_calibration.hpp"
#include "test_util/temp_dir.hpp"
#include "test_util/test_util.hpp"

namespace telear::sim {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

constexpr int kWholeViews = 14;
constexpr int kPartialViews = 8;

// Inner corners of `target` that project at least 3 px inside the camera's image.
int visible_corners(const vision::CameraModel& camera, const CalibrationTarget& target,
                    const Eigen::Isometry3d& T_base_target) {
  int count = 0;
  for (const Eigen::Vector3d& p : target.points_target) {
    const auto uv = camera.project(T_base_target * p);
    if (uv && uv->x() > 2.5 && uv->y() > 2.5 && uv->x() < camera.width - 3.5 &&
        uv->y() < camera.height - 3.5) {
      ++count;
    }
  }
  return count;
}

// `pose` moved along the camera's image x axis by the first multiple of 5 mm (in the
// direction `sign`) after which `accept(visible corners)` holds.
Eigen::Isometry3d slid_out(const vision::CameraModel& camera, const CalibrationTarget& target,
                           Eigen::Isometry3d pose, double sign,
                           const std::function<bool(int)>& accept) {
  const Eigen::Vector3d x_base = camera.T_cam_base.inverse().linear().col(0);
  for (int step = 0; step < 200; ++step) {
    if (accept(visible_corners(camera, target, pose))) return pose;
    pose.translation() += sign * 0.005 * x_base;
  }
  ADD_FAILURE() << "no slid pose found";
  return pose;
}

class CharucoCalibrationTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    auto rig = load_stereo_rig(test::data_path("rigs/puma560_rig.yaml"));
    ASSERT_TRUE(rig.ok()) << rig.error().message;
    rig_ = new StereoRig(std::move(*rig));
    auto pattern = vision::parse_calibration_pattern("charuco:9x7:0.025:0.018:4x4_50");
    ASSERT_TRUE(pattern.ok()) << pattern.error().message;
    pattern_ = *pattern;
    const CalibrationTarget target = make_calibration_target(pattern_, 0.5);
    auto poses = calibration_target_poses(rig_->cameras, rig_->T_base_rig, target,
                                          kWholeViews + kPartialViews + 1, 7);
    ASSERT_TRUE(poses.ok()) << poses.error().message;
    const vision::CameraModel& left = rig_->cameras.left;
    const int all = pattern_.point_count();
    // Views 14..21: 40-70 % of the corners in the left image, slid out to either side.
    for (int k = kWholeViews; k < kWholeViews + kPartialViews; ++k) {
      (*poses)[k] = slid_out(left, target, (*poses)[k], k % 2 == 0 ? 1.0 : -1.0,
                             [all](int n) { return n >= 0.4 * all && n <= 0.7 * all; });
    }
    // The last view: the board all but gone, at most one column of corners in the image.
    poses->back() =
        slid_out(left, target, poses->back(), 1.0, [](int n) { return n > 0 && n <= 6; });
    sliver_ = kWholeViews + kPartialViews;

    // One folder per process: CTest runs each test of this suite as its own process, in
    // parallel, and a shared folder let one process read images another was rewriting.
    dir_ = new test_files::TempDir("charuco_calibration");
    const TargetImageRenderer left_renderer(rig_->cameras.left);
    const TargetImageRenderer right_renderer(rig_->cameras.right);
    for (std::size_t k = 0; k < poses->size(); ++k) {
      char name[32];
      std::snprintf(name, sizeof name, "%02zu.png", k);
      left_paths_.push_back(dir_->file(std::string("left_") + name));
      right_paths_.push_back(dir_->file(std::string("right_") + name));
      ASSERT_TRUE(vision::write_png_file(left_paths_.back(),
                                         left_renderer.render(target, (*poses)[k], 4, 1.0, 2 * k)));
      ASSERT_TRUE(vision::write_png_file(
          right_paths_.back(), right_renderer.render(target, (*poses)[k], 4, 1.0, 2 * k + 1)));
    }
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
    delete rig_;
    rig_ = nullptr;
  }

  static void expect_recovered(const char* eye, const vision::CameraModel& found,
                               const vision::CameraModel& truth) {
    const double fx = (found.fx - truth.fx) / truth.fx, fy = (found.fy - truth.fy) / truth.fy;
    std::cout << eye << ": fx " << found.fx << " (true " << truth.fx << ", " << 100 * fx
              << " %), fy " << found.fy << " (true " << truth.fy << ", " << 100 * fy << " %), cx "
              << found.cx << " (true " << truth.cx << "), cy " << found.cy << " (true " << truth.cy
              << ")\n";
    EXPECT_LT(std::abs(fx), 0.002) << eye;
    EXPECT_LT(std::abs(fy), 0.002) << eye;
    EXPECT_LT(std::abs(found.cx - truth.cx), 1.0) << eye;
    EXPECT_LT(std::abs(found.cy - truth.cy), 1.0) << eye;
  }

  static StereoRig* rig_;
  static vision::CalibrationPattern pattern_;
  static test_files::TempDir* dir_;
  static std::vector<std::string> left_paths_, right_paths_;
  static int sliver_;
};
StereoRig* CharucoCalibrationTest::rig_ = nullptr;
vision::CalibrationPattern CharucoCalibrationTest::pattern_;
test_files::TempDir* CharucoCalibrationTest::dir_ = nullptr;
std::vector<std::string> CharucoCalibrationTest::left_paths_, CharucoCalibrationTest::right_paths_;
int CharucoCalibrationTest::sliver_ = 0;

TEST_F(CharucoCalibrationTest, MonoFromWholeAndPartialViewsRecoversTheTrueCamera) {
  auto detected = vision::detect_in_images(left_paths_, pattern_);
  ASSERT_TRUE(detected.ok()) << detected.error().message;
  int partial = 0;
  for (const vision::PatternView& view : detected->views) {
    ASSERT_EQ(view.object_points.size(), view.image_points.size()) << view.name;
    if (static_cast<int>(view.image_points.size()) < pattern_.point_count()) ++partial;
  }
  std::cout << detected->views.size() << " views, " << partial << " of them partial\n";
  EXPECT_GE(partial, kPartialViews - 1);
  EXPECT_GE(detected->views.size(), static_cast<std::size_t>(kWholeViews + kPartialViews - 1));

  // The view with one column of corners or fewer is named, with the count, in the report.
  ASSERT_EQ(detected->rejected.size(), 1u);
  EXPECT_EQ(detected->rejected[0].name, left_paths_[static_cast<std::size_t>(sliver_)]);
  EXPECT_THAT(detected->rejected[0].reason, HasSubstr("ChArUco corner"));
  std::cout << "rejected " << vision::file_name_of(detected->rejected[0].name) << ": "
            << detected->rejected[0].reason << "\n";

  auto calibration = vision::calibrate_mono(pattern_, detected->views, detected->image_size);
  ASSERT_TRUE(calibration.ok()) << calibration.error().message;
  std::cout << "mono RMS " << calibration->rms_px << " px\n";
  EXPECT_LT(calibration->rms_px, 0.2);
  expect_recovered("left (mono)", calibration->camera, rig_->cameras.left);
}

TEST_F(CharucoCalibrationTest, StereoUsesTheCornersBothImagesShow) {
  auto detected = vision::detect_in_image_pairs(left_paths_, right_paths_, pattern_);
  ASSERT_TRUE(detected.ok()) << detected.error().message;
  int partial = 0;
  for (const vision::StereoPatternView& view : detected->views) {
    ASSERT_EQ(view.left_points.size(), view.right_points.size()) << view.left_name;
    ASSERT_EQ(view.object_points.size(), view.left_points.size()) << view.left_name;
    if (static_cast<int>(view.left_points.size()) < pattern_.point_count()) ++partial;
  }
  std::cout << detected->views.size() << " pairs, " << partial << " of them partial\n";
  EXPECT_GE(partial, kPartialViews / 2);
  for (const vision::RejectedView& rejected : detected->rejected) {
    std::cout << "rejected " << vision::file_name_of(rejected.name) << ": " << rejected.reason
              << "\n";
  }

  auto calibration = vision::calibrate_stereo(pattern_, detected->views, detected->image_size);
  ASSERT_TRUE(calibration.ok()) << calibration.error().message;
  std::cout << "stereo RMS " << calibration->rms_px << " px, baseline "
            << 1000 * calibration->baseline() << " mm (true " << 1000 * rig_->baseline_m
            << " mm)\n";
  expect_recovered("left (stereo)", calibration->cameras.left, rig_->cameras.left);
  expect_recovered("right (stereo)", calibration->cameras.right, rig_->cameras.right);
  EXPECT_NEAR(calibration->baseline(), rig_->baseline_m, 0.001);
}

// The CPU renderer draws the board where the camera model projects it: the ChArUco corners
// found in a whole view lie on the true projections of the target's corners.
TEST_F(CharucoCalibrationTest, RenderedCornersLieOnTheTrueProjection) {
  auto read = vision::read_image_file(left_paths_[0], vision::ImageFileMode::kGrey);
  ASSERT_TRUE(read) << read.error().message;
  const cv::Mat image = *read;
  auto found = vision::detect_pattern(image, pattern_);
  ASSERT_TRUE(found.ok()) << found.error().message;
  const CalibrationTarget target = make_calibration_target(pattern_, 0.5);
  auto poses = calibration_target_poses(rig_->cameras, rig_->T_base_rig, target, 1, 7);
  ASSERT_TRUE(poses.ok());
  double worst = 0.0;
  for (std::size_t k = 0; k < found->size(); ++k) {
    const auto uv = rig_->cameras.left.project((*poses)[0] * target.points_target[k]);
    ASSERT_TRUE(uv.has_value());
    worst = std::max(worst, std::hypot((*found)[k].x - uv->x(), (*found)[k].y - uv->y()));
  }
  std::cout << "worst corner error " << worst << " px\n";
  EXPECT_LT(worst, 0.25);
}

// The mesh the scene renderer draws (telear sim capture) is the same board: every black
// triangle at z = 0 lies where the layout is black, the white plate behind it covers the
// board and its margin, and the mesh has a triangle for every black square and marker cell.
TEST(CharucoTarget, MeshIsTheLayout) {
  auto pattern = vision::parse_calibration_pattern("charuco:7x5:0.04:0.03:4x4_50");
  ASSERT_TRUE(pattern.ok());
  const CalibrationTarget target = make_calibration_target(*pattern, 1.0);
  EXPECT_NEAR(target.outline_min.x(), -0.04, 1e-12);
  EXPECT_NEAR(target.outline_max.x(), 0.32, 1e-12);
  EXPECT_NEAR(target.outline_max.y(), 0.24, 1e-12);
  ASSERT_EQ(target.points_target.size(), 24u);
  EXPECT_NEAR(target.points_target[7].x(), 0.08, 1e-7);  // id 7: row 1, column 1
  EXPECT_NEAR(target.points_target[7].y(), 0.08, 1e-7);
  int black = 0, plate = 0;
  for (std::size_t t = 0; t < target.mesh.triangles.size(); t += 3) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      const float* p = target.mesh.vertices[target.mesh.triangles[t + k]].position;
      centroid += Eigen::Vector3d(p[0], p[1], p[2]) / 3.0;
    }
    if (centroid.z() > 0.0001) {
      ++plate;
      continue;
    }
    ++black;
    EXPECT_EQ(target.reflectance(centroid.x(), centroid.y()), 0.0)
        << centroid.x() << " " << centroid.y();
  }
  EXPECT_EQ(plate, 2);
  // 18 black squares and the black cells of 17 markers, two triangles each.
  int cells = 0;
  for (const vision::CharucoMarker& marker : target.charuco.markers) {
    cells += marker.cells.rows * marker.cells.cols - cv::countNonZero(marker.cells);
  }
  EXPECT_EQ(black, 2 * (18 + cells));
  EXPECT_EQ(target.reflectance(-0.02, 0.1), 1.0);   // the margin
  EXPECT_EQ(target.reflectance(-0.05, 0.1), -1.0);  // beyond it
}

}  // namespace
}  // namespace telear::sim
