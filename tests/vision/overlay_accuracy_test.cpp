// The overlay error metric: identical cameras give 0 px; a known pixel shift of the principal
// point gives that shift; a registration from noisy synthetic observations stays under the
// issue's targets (<= 0.5 px RMS, <= 1.5 px max per eye).

#include "telear/vision/overlay_accuracy.hpp"

#include <gtest/gtest.h>

#include <random>

#include "synthetic_observations.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/vision/camera_file.hpp"
#include "telear/vision/registration.hpp"
#include "test_util/test_util.hpp"

namespace telear::vision {
namespace {

core::ArmBody puma_body(const core::RobotModel& model) {
  Result<core::BodyDescription> description = core::body_description_for(model);
  EXPECT_TRUE(description.ok()) << (description.ok() ? "" : description.error().message);
  return core::build_arm_body(*description);
}

TEST(OverlayAccuracy, SamplesCoverEveryLinkDensely) {
  const core::RobotModelPtr model = test::puma560();
  const core::ArmBody body = puma_body(*model);
  const std::vector<LinkSamples> samples = sample_arm_body(body, 0.01);
  std::vector<bool> seen(static_cast<std::size_t>(model->dof() + 1), false);
  for (const LinkSamples& s : samples) seen[static_cast<std::size_t>(s.link)] = !s.p_link.empty();
  for (int link = 1; link <= model->dof(); ++link) {
    EXPECT_TRUE(seen[static_cast<std::size_t>(link)]) << "link " << link;
  }
  // Finer spacing gives more points.
  std::size_t coarse = 0, fine = 0;
  for (const LinkSamples& s : sample_arm_body(body, 0.05)) coarse += s.p_link.size();
  for (const LinkSamples& s : samples) fine += s.p_link.size();
  EXPECT_GT(fine, 2 * coarse);
}

TEST(OverlayAccuracy, IdenticalCamerasAndAKnownShift) {
  const core::RobotModelPtr model = test::puma560();
  const StereoCameraModel truth = test::shipped_stereo_cameras();
  const core::ArmBody body = puma_body(*model);
  AccuracyOptions options;
  options.configurations = 10;
  const AccuracyReport same = evaluate_accuracy(*model, body, truth, truth, options);
  EXPECT_GT(same.left.overlay.points, 1000);
  EXPECT_EQ(same.left.overlay.rms_px, 0.0);
  EXPECT_EQ(same.right.overlay.max_px, 0.0);
  EXPECT_NEAR(same.baseline_truth_m, 0.06, 1e-9);
  EXPECT_EQ(same.left.registration.position_mm, 0.0);

  // Moving the principal point by (0.3, 0.4) px moves every pixel by 0.5 px exactly.
  StereoCameraModel shifted = truth;
  shifted.left.cx += 0.3;
  shifted.left.cy += 0.4;
  const AccuracyReport shift = evaluate_accuracy(*model, body, truth, shifted, options);
  EXPECT_NEAR(shift.left.overlay.rms_px, 0.5, 1e-9);
  EXPECT_NEAR(shift.left.overlay.max_px, 0.5, 1e-9);
  EXPECT_EQ(shift.right.overlay.rms_px, 0.0);

  // A 1 mm camera displacement along the base x axis: registration error 1 mm, 0 deg.
  StereoCameraModel moved = truth;
  moved.right.T_cam_base =
      truth.right.T_cam_base * Eigen::Translation3d(Eigen::Vector3d(-0.001, 0.0, 0.0));
  const AccuracyReport move = evaluate_accuracy(*model, body, truth, moved, options);
  EXPECT_NEAR(move.right.registration.position_mm, 1.0, 1e-9);
  EXPECT_NEAR(move.right.registration.rotation_deg, 0.0, 1e-6);
  EXPECT_NEAR(move.baseline_estimate_m,
              (truth.right.T_cam_base.inverse().translation() + Eigen::Vector3d(0.001, 0, 0) -
               truth.left.T_cam_base.inverse().translation())
                  .norm(),
              1e-9);
}

TEST(OverlayAccuracy, RegisteredRigStaysUnderTarget) {
  const core::RobotModelPtr model = test::puma560();
  const StereoCameraModel truth = test::shipped_stereo_cameras();
  // Marker corners at 20 random configurations where both eyes see them, 0.1 px noise.
  const RegistrationObservations observations =
      test::synthetic_observations(*model, truth, test::flange_marker_corners(), 20, 0.1, 21);
  Result<RegistrationResult> registration =
      register_stereo(*model, truth.left, truth.right,
                      right_from_left(truth.left.T_cam_base, truth.right.T_cam_base), observations);
  ASSERT_TRUE(registration.ok()) << registration.error().message;
  StereoCameraModel estimate = truth;
  estimate.left.T_cam_base = registration->T_left_base;
  estimate.right.T_cam_base = registration->T_right_base;
  const AccuracyReport report = evaluate_accuracy(*model, puma_body(*model), truth, estimate);
  std::printf(
      "overlay: left %.3f px RMS %.3f px max, right %.3f / %.3f (%ld, %ld points); "
      "registration %.3f mm %.4f deg\n",
      report.left.overlay.rms_px, report.left.overlay.max_px, report.right.overlay.rms_px,
      report.right.overlay.max_px, report.left.overlay.points, report.right.overlay.points,
      report.left.registration.position_mm, report.left.registration.rotation_deg);
  EXPECT_LE(report.left.overlay.rms_px, 0.5);
  EXPECT_LE(report.left.overlay.max_px, 1.5);
  EXPECT_LE(report.right.overlay.rms_px, 0.5);
  EXPECT_LE(report.right.overlay.max_px, 1.5);
  EXPECT_LT(report.left.registration.position_mm, 1.0);
  EXPECT_LT(report.left.registration.rotation_deg, 0.1);
}

}  // namespace
}  // namespace telear::vision
