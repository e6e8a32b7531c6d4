// Calibration against a known truth: corner lists projected from the synthetic rig with
// 0.1 px noise (issue 4's targets: fx, fy within 0.2 %, cc within 1 px, baseline within
// 0.5 mm), outlier rejection, and the errors of bad input.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <iostream>
#include <opencv2/calib3d.hpp>

#include "synthetic_observations.hpp"
#include "synthetic_views.hpp"
#include "telear/vision/mono_calibration.hpp"
#include "telear/vision/stereo_calibration.hpp"

namespace telear::vision {
namespace {

using ::testing::HasSubstr;

using test::chessboard_9x6;

std::vector<PatternView> left_views(const std::vector<StereoPatternView>& stereo) {
  std::vector<PatternView> views;
  for (const StereoPatternView& v : stereo) views.push_back({v.left_name, v.left_points});
  return views;
}

struct Synthetic {
  test::SyntheticRig rig = test::default_rig();
  std::vector<Eigen::Isometry3d> poses;
  std::vector<StereoPatternView> views;
};

Synthetic synthetic(int count, double noise_px, std::uint64_t seed) {
  Synthetic s;
  std::mt19937_64 rng(seed);
  s.poses = test::random_pattern_poses(s.rig, chessboard_9x6(), count, rng);
  EXPECT_EQ(static_cast<int>(s.poses.size()), count);
  s.views = test::stereo_views(s.rig, chessboard_9x6(), s.poses, noise_px, rng);
  return s;
}

void print_row(const char* name, double truth, double estimate, double std_dev) {
  std::printf("  %-10s %12.5f %12.5f %12.5f %10.5f\n", name, truth, estimate, estimate - truth,
              std_dev);
}

void print_camera(const char* title, const CameraModel& truth, const CameraModel& estimate,
                  const IntrinsicsStdDev& sd) {
  std::printf("%s\n  %-10s %12s %12s %12s %10s\n", title, "parameter", "truth", "estimate", "error",
              "1-sigma");
  print_row("fx [px]", truth.fx, estimate.fx, sd.fx);
  print_row("fy [px]", truth.fy, estimate.fy, sd.fy);
  print_row("cx [px]", truth.cx, estimate.cx, sd.cx);
  print_row("cy [px]", truth.cy, estimate.cy, sd.cy);
  print_row("k1", truth.kc.k1, estimate.kc.k1, sd.kc.k1);
  print_row("k2", truth.kc.k2, estimate.kc.k2, sd.kc.k2);
  print_row("p1", truth.kc.p1, estimate.kc.p1, sd.kc.p1);
  print_row("p2", truth.kc.p2, estimate.kc.p2, sd.kc.p2);
  print_row("k3", truth.kc.k3, estimate.kc.k3, sd.kc.k3);
}

// fx, fy within the 0.2 %, and the true error of each parameter within 4 of the
// reported standard deviations (checks the reported uncertainty too). The principal point's
// 1 px target is checked over several seeds (StereoCalibration.MeetsTheAccuracyTargets): its
// standard deviation with 20 views of a 9x6 board and 0.1 px noise is about 0.5 px.
void expect_recovered(const CameraModel& truth, const CameraModel& estimate,
                      const IntrinsicsStdDev& sd) {
  EXPECT_LT(std::abs(estimate.fx / truth.fx - 1.0), 0.002);
  EXPECT_LT(std::abs(estimate.fy / truth.fy - 1.0), 0.002);
  EXPECT_LT(std::abs(estimate.fx - truth.fx), 4.0 * sd.fx);
  EXPECT_LT(std::abs(estimate.fy - truth.fy), 4.0 * sd.fy);
  EXPECT_LT(std::abs(estimate.cx - truth.cx), 4.0 * sd.cx);
  EXPECT_LT(std::abs(estimate.cy - truth.cy), 4.0 * sd.cy);
  EXPECT_LT(std::abs(estimate.kc.k1 - truth.kc.k1), 4.0 * sd.kc.k1);
  EXPECT_LT(std::abs(estimate.kc.p1 - truth.kc.p1), 4.0 * sd.kc.p1);
  EXPECT_LT(std::abs(estimate.kc.p2 - truth.kc.p2), 4.0 * sd.kc.p2);
  EXPECT_GT(sd.fx, 0.0);
  EXPECT_LT(sd.cx, 3.0);
}

// 0.1 px of noise on each coordinate is 0.1 sqrt(2) px of 2-D error; the fit absorbs a
// little of it (about 1 - parameters / residuals).
constexpr double kNoiseRms = 0.1 * M_SQRT2;

TEST(MonoCalibration, RecoversTheTrueCameraFromNoisyCorners) {
  const Synthetic s = synthetic(20, 0.1, 20240601);
  const auto result = calibrate_mono(chessboard_9x6(), left_views(s.views), {640, 480});
  ASSERT_TRUE(result.ok()) << result.error().message;
  print_camera("mono, 20 views, 0.1 px noise", s.rig.left, result->camera, result->std_dev);
  std::printf("  rms %.4f px\n", result->rms_px);
  expect_recovered(s.rig.left, result->camera, result->std_dev);
  EXPECT_NEAR(result->rms_px, kNoiseRms, 0.01);
  EXPECT_TRUE(result->rejected.empty());
  ASSERT_EQ(result->views.size(), 20u);
  // Poses: the true pattern pose of each view, to a millimetre or so.
  for (std::size_t i = 0; i < result->views.size(); ++i) {
    const Eigen::Vector3d dt =
        result->views[i].T_cam_target.translation() - s.poses[i].translation();
    EXPECT_LT(dt.norm(), 5.0 * result->views[i].translation_std.norm()) << i;
    EXPECT_LT(dt.norm(), 3e-3) << i;
    EXPECT_EQ(result->views[i].name, s.views[i].left_name);
  }
}

TEST(MonoCalibration, NoiseFreeCornersGiveTheTruthExactly) {
  const Synthetic s = synthetic(8, 0.0, 7);
  const auto result = calibrate_mono(chessboard_9x6(), left_views(s.views), {640, 480});
  ASSERT_TRUE(result.ok()) << result.error().message;
  EXPECT_LT(result->rms_px, 1e-3);
  EXPECT_NEAR(result->camera.fx, s.rig.left.fx, 0.01);
  EXPECT_NEAR(result->camera.cy, s.rig.left.cy, 0.01);
  EXPECT_NEAR(result->camera.kc.k1, s.rig.left.kc.k1, 1e-4);
  EXPECT_EQ(result->camera.alpha_c, 0.0);
  EXPECT_TRUE(result->camera.T_cam_base.isApprox(Eigen::Isometry3d::Identity()));
}

TEST(MonoCalibration, WorksWithTheAsymmetricCircleGrid) {
  const CalibrationPattern circles = *parse_calibration_pattern("circles:4x11:0.02");
  std::mt19937_64 rng(31);
  const test::SyntheticRig rig = test::default_rig();
  const auto poses = test::random_pattern_poses(rig, circles, 15, rng);
  ASSERT_EQ(poses.size(), 15u);
  std::vector<PatternView> views;
  for (const Eigen::Isometry3d& pose : poses) {
    views.push_back({"circles", test::project_pattern(rig.left, pose, circles, 0.1, rng)});
  }
  const auto result = calibrate_mono(circles, views, {640, 480});
  ASSERT_TRUE(result.ok()) << result.error().message;
  expect_recovered(rig.left, result->camera, result->std_dev);
  EXPECT_NEAR(result->rms_px, kNoiseRms, 0.01);
}

TEST(MonoCalibration, RejectsAnOutlierViewAndSaysWhy) {
  Synthetic s = synthetic(12, 0.1, 99);
  // View 5's corners displaced by a smooth 2 px warp (a bent board, a wrong detection).
  for (cv::Point2f& p : s.views[5].left_points)
    p += cv::Point2f(0.004f * (p.y - 240.0f), 1.5f * std::sin(p.x / 60.0f));
  const auto result = calibrate_mono(chessboard_9x6(), left_views(s.views), {640, 480});
  ASSERT_TRUE(result.ok()) << result.error().message;
  ASSERT_EQ(result->rejected.size(), 1u);
  EXPECT_EQ(result->rejected[0].name, "view05_left");
  EXPECT_THAT(result->rejected[0].reason, HasSubstr("outlier: reprojection RMS "));
  EXPECT_THAT(result->rejected[0].reason, HasSubstr(" > 3 x median 0.1"));
  EXPECT_EQ(result->views.size(), 11u);
  EXPECT_LT(result->rms_px, kNoiseRms + 0.01);
  expect_recovered(s.rig.left, result->camera, result->std_dev);

  CalibrationOptions keep_all;
  keep_all.outlier_factor = 0.0;
  const auto kept = calibrate_mono(chessboard_9x6(), left_views(s.views), {640, 480}, keep_all);
  ASSERT_TRUE(kept.ok());
  EXPECT_TRUE(kept->rejected.empty());
  EXPECT_GT(kept->rms_px, 1.5 * result->rms_px);
}

TEST(MonoCalibration, BadInputIsAnErrorThatSaysWhatToDo) {
  const Synthetic s = synthetic(5, 0.1, 3);
  std::vector<PatternView> views = left_views(s.views);

  auto few = calibrate_mono(chessboard_9x6(), {views[0], views[1]}, {640, 480});
  ASSERT_FALSE(few.ok());
  EXPECT_THAT(few.error().message,
              HasSubstr("too few views: 2 usable views (need at least 3); capture more images"));

  std::vector<PatternView> short_view = views;
  short_view[2].image_points.pop_back();
  auto wrong = calibrate_mono(chessboard_9x6(), short_view, {640, 480});
  ASSERT_FALSE(wrong.ok());
  EXPECT_EQ(wrong.error().message,
            "view 'view02_left' has 53 points but pattern chessboard:9x6:0.03 has 54");

  auto size = calibrate_mono(chessboard_9x6(), views, {0, 480});
  ASSERT_FALSE(size.ok());
  EXPECT_THAT(size.error().message, HasSubstr("image size 0x480 is not positive"));

  CalibrationOptions options;
  options.outlier_factor = 0.5;
  auto bad_options = calibrate_mono(chessboard_9x6(), views, {640, 480}, options);
  ASSERT_FALSE(bad_options.ok());
  EXPECT_THAT(bad_options.error().message, HasSubstr("outlier_factor must be 0"));

  // Every view the same: Zhang's method has nothing to work with.
  std::vector<PatternView> same(4, views[0]);
  auto degenerate = calibrate_mono(chessboard_9x6(), same, {640, 480});
  if (degenerate.ok()) {
    // OpenCV may return a solution for identical views; it cannot be the truth.
    EXPECT_GT(std::abs(degenerate->camera.fx - s.rig.left.fx) +
                  std::abs(degenerate->camera.cx - s.rig.left.cx),
              0.5);
  } else {
    EXPECT_THAT(degenerate.error().message, HasSubstr("tilted in different directions"));
  }
}

TEST(StereoCalibration, RecoversTheRigAndTheBaseline) {
  const Synthetic s = synthetic(20, 0.1, 20240601);
  const auto result = calibrate_stereo(chessboard_9x6(), s.views, {640, 480});
  ASSERT_TRUE(result.ok()) << result.error().message;
  print_camera("stereo left, 20 pairs, 0.1 px noise", s.rig.left, result->cameras.left,
               result->left_std_dev);
  print_camera("stereo right", s.rig.right, result->cameras.right, result->right_std_dev);
  const double true_baseline = s.rig.T_right_left.translation().norm();
  std::printf("  baseline   %12.7f %12.7f %12.7f %10.7f (m)\n", true_baseline, result->baseline(),
              result->baseline() - true_baseline, result->baseline_std);
  std::printf("  rms %.4f px (left %.4f, right %.4f; alone %.4f, %.4f)\n", result->rms_px,
              result->left_rms_px, result->right_rms_px, result->mono_left_rms_px,
              result->mono_right_rms_px);
  expect_recovered(s.rig.left, result->cameras.left, result->left_std_dev);
  expect_recovered(s.rig.right, result->cameras.right, result->right_std_dev);

  EXPECT_LT(std::abs(result->baseline() - true_baseline), 0.5e-3);
  EXPECT_LT(std::abs(result->baseline() - true_baseline), 4.0 * result->baseline_std);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(result->T[i], s.rig.T_right_left.translation()(i),
                4.0 * result->translation_std(i) + 1e-6);
  }
  Eigen::Matrix3d R;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) R(r, c) = result->R(r, c);
  }
  const double angle_error = Eigen::AngleAxisd(R * s.rig.T_right_left.linear().transpose()).angle();
  EXPECT_LT(angle_error, 4.0 * result->rotation_std.norm());
  EXPECT_LT(angle_error, 0.3 * M_PI / 180.0);

  // The camera models carry the stereo geometry: the base frame is the left camera.
  EXPECT_TRUE(result->cameras.left.T_cam_base.isApprox(Eigen::Isometry3d::Identity()));
  EXPECT_TRUE(result->cameras.right.T_cam_base.linear().isApprox(R, 1e-12));
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(result->cameras.right.T_cam_base.translation()(i), result->T[i]);
  }

  // The RMS telear recomputes at its own left poses equals stereoCalibrate's figure: the
  // covariance was evaluated at the optimum.
  const double both = std::sqrt(0.5 * (result->left_rms_px * result->left_rms_px +
                                       result->right_rms_px * result->right_rms_px));
  EXPECT_NEAR(both, result->rms_px, 1e-6 * result->rms_px + 1e-9);
  EXPECT_NEAR(result->rms_px, kNoiseRms, 0.01);

  // Rectification: same row in both rectified images, P2 holds -f * baseline.
  const StereoRectification& rect = result->rectification;
  EXPECT_NEAR(rect.P2(0, 3) / rect.P2(0, 0), -result->baseline(), 1e-9);
  EXPECT_NEAR(rect.P1(1, 1), rect.P2(1, 1), 1e-9);
  EXPECT_GT(rect.left_roi.area(), 0);
  ASSERT_EQ(result->views.size(), 20u);
  EXPECT_TRUE(result->rejected.empty());
}

TEST(StereoCalibration, MeetsTheAccuracyTargetsOverSeeds) {
  // Issue 4's targets, 20 pairs, 0.1 px noise: fx, fy within 0.2 % and the baseline within
  // 0.5 mm in every run; the principal point within 1 px as the RMS over runs and
  // coordinates (one run's error is a draw with a standard deviation of about 0.5 px).
  std::printf("seed  max|dfx/fx|  max|dfy/fy|  max|dc| px  |db| mm   rms px\n");
  double cc_squares = 0.0;
  int cc_count = 0;
  for (std::uint64_t seed : {101u, 102u, 103u, 104u, 105u}) {
    const Synthetic s = synthetic(20, 0.1, seed);
    const auto r = calibrate_stereo(chessboard_9x6(), s.views, {640, 480});
    ASSERT_TRUE(r.ok()) << r.error().message;
    double fx = 0.0, fy = 0.0, cc = 0.0;
    for (const auto& [truth, estimate] :
         {std::pair{&s.rig.left, &r->cameras.left}, std::pair{&s.rig.right, &r->cameras.right}}) {
      fx = std::max(fx, std::abs(estimate->fx / truth->fx - 1.0));
      fy = std::max(fy, std::abs(estimate->fy / truth->fy - 1.0));
      for (double d : {estimate->cx - truth->cx, estimate->cy - truth->cy}) {
        cc = std::max(cc, std::abs(d));
        cc_squares += d * d;
        ++cc_count;
      }
    }
    const double db = std::abs(r->baseline() - s.rig.T_right_left.translation().norm());
    std::printf("%4d  %10.5f  %11.5f  %10.3f  %6.4f  %7.4f\n", static_cast<int>(seed), fx, fy, cc,
                1e3 * db, r->rms_px);
    EXPECT_LT(fx, 0.002) << seed;
    EXPECT_LT(fy, 0.002) << seed;
    EXPECT_LT(db, 0.5e-3) << seed;
  }
  const double cc_rms = std::sqrt(cc_squares / cc_count);
  std::printf("principal point error, RMS over runs: %.3f px\n", cc_rms);
  EXPECT_LT(cc_rms, 1.0);
}

TEST(StereoCalibration, JointRefinementIsAtLeastAsAccurateAsFixedMonoIntrinsics) {
  // The design choice in stereo_calibration.hpp, measured over several seeds: the joint
  // solution's summed squared error in the intrinsics and baseline is the smaller one.
  double joint_error = 0.0, fixed_error = 0.0;
  for (std::uint64_t seed : {11u, 12u, 13u, 14u}) {
    const Synthetic s = synthetic(12, 0.1, seed);
    StereoCalibrationOptions fixed;
    fixed.refine_intrinsics = false;
    const auto a = calibrate_stereo(chessboard_9x6(), s.views, {640, 480});
    const auto b = calibrate_stereo(chessboard_9x6(), s.views, {640, 480}, fixed);
    ASSERT_TRUE(a.ok() && b.ok());
    auto error = [&s](const StereoCalibration& c) {
      const double true_baseline = s.rig.T_right_left.translation().norm();
      return std::pow(c.cameras.left.fx - s.rig.left.fx, 2) +
             std::pow(c.cameras.right.fx - s.rig.right.fx, 2) +
             std::pow(c.cameras.left.cx - s.rig.left.cx, 2) +
             std::pow(c.cameras.right.cy - s.rig.right.cy, 2) +
             std::pow(1e3 * (c.baseline() - true_baseline), 2);
    };
    joint_error += error(*a);
    fixed_error += error(*b);
    EXPECT_LE(a->rms_px, b->rms_px + 1e-9);
  }
  std::printf("summed squared error (px^2 + mm^2): joint %.4f, fixed mono intrinsics %.4f\n",
              joint_error, fixed_error);
  EXPECT_LT(joint_error, fixed_error);
}

TEST(StereoCalibration, RejectsAnOutlierPairInEitherImage) {
  Synthetic s = synthetic(12, 0.1, 5);
  for (cv::Point2f& p : s.views[7].right_points)
    p += cv::Point2f(1.5f * std::cos(p.y / 50.0f), 0.004f * (p.x - 320.0f));
  const auto result = calibrate_stereo(chessboard_9x6(), s.views, {640, 480});
  ASSERT_TRUE(result.ok()) << result.error().message;
  ASSERT_EQ(result->rejected.size(), 1u);
  EXPECT_EQ(result->rejected[0].name, "view07_left");
  EXPECT_EQ(result->rejected[0].right_name, "view07_right");
  EXPECT_THAT(result->rejected[0].reason, HasSubstr("outlier: right reprojection RMS"));
  EXPECT_EQ(result->views.size(), 11u);
  EXPECT_LT(std::abs(result->baseline() - s.rig.T_right_left.translation().norm()), 0.5e-3);
}

TEST(StereoCalibration, BadInputIsAnErrorThatSaysWhatToDo) {
  const Synthetic s = synthetic(4, 0.1, 8);
  auto few = calibrate_stereo(chessboard_9x6(), {s.views[0], s.views[1]}, {640, 480});
  ASSERT_FALSE(few.ok());
  EXPECT_THAT(few.error().message,
              HasSubstr("too few views: 2 usable stereo pairs (need at least 3)"));

  std::vector<StereoPatternView> bad = s.views;
  bad[1].right_points.resize(10);
  auto wrong = calibrate_stereo(chessboard_9x6(), bad, {640, 480});
  ASSERT_FALSE(wrong.ok());
  EXPECT_THAT(wrong.error().message, HasSubstr("view 'view01_right' has 10 points"));

  StereoCalibrationOptions options;
  options.rectify_alpha = 2.0;
  auto alpha = calibrate_stereo(chessboard_9x6(), s.views, {640, 480}, options);
  ASSERT_FALSE(alpha.ok());
  EXPECT_THAT(alpha.error().message, HasSubstr("rectify_alpha must be"));
}

}  // namespace
}  // namespace telear::vision
