// Hand-eye registration (the base in both cameras and the target on the flange, jointly) on
// synthetic observations: the shipped stereo rig is the truth, the PUMA 560 carries a marker
// at a pose on the flange that the solver is not told, the true cameras project its corners
// (with distortion) plus Gaussian pixel noise.

#include "telear/vision/hand_eye_registration.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <random>

#include "synthetic_observations.hpp"
#include "telear/core/angles.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/vision/overlay_accuracy.hpp"
#include "test_util/test_util.hpp"

namespace telear::vision {
namespace {

using ::testing::HasSubstr;

// The marker in its own frame (OpenCV's aruco corner order), 8 cm.
std::vector<Eigen::Vector3d> marker_points() {
  const double h = 0.04;
  return {{-h, h, 0}, {h, h, 0}, {h, -h, 0}, {-h, -h, 0}};
}

// Where it really sits on the flange: 6 cm out, turned and tilted (unknown to the solver).
Eigen::Isometry3d true_T_flange_target() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = (Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(-0.2, Eigen::Vector3d::UnitX()))
                   .matrix();
  T.translation() = Eigen::Vector3d(0.01, -0.005, 0.06);
  return T;
}

using test::T_right_left_of;

// Observations of the marker at `count` random configurations both eyes see it at.
HandEyeObservations synthetic(const core::RobotModel& model, const StereoCameraModel& truth,
                              int count, double noise_px, unsigned seed) {
  std::vector<Eigen::Vector3d> in_flange;
  for (const auto& p : marker_points()) in_flange.push_back(true_T_flange_target() * p);
  HandEyeObservations observations = hand_eye_observations(
      test::synthetic_observations(model, truth, in_flange, count, noise_px, seed));
  observations.target_points = marker_points();
  return observations;
}

double angle_deg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return core::degrees_from_radians(
      Eigen::AngleAxisd(Eigen::Matrix3d(a.linear().transpose() * b.linear())).angle());
}

class HandEyeRegistration : public ::testing::Test {
 protected:
  core::RobotModelPtr model = test::puma560();
  StereoCameraModel truth = test::shipped_stereo_cameras();
};

TEST_F(HandEyeRegistration, RecoversTheBaseAndTheTargetBetterThanShahLi) {
  const HandEyeObservations observations = synthetic(*model, truth, 30, 0.1, 11);
  Result<HandEyeResult> result =
      register_hand_eye(*model, truth.left, truth.right, T_right_left_of(truth), observations);
  ASSERT_TRUE(result.ok()) << result.error().message;
  const PoseError left = registration_error(truth.left.T_cam_base, result->T_left_base);
  const PoseError right = registration_error(truth.right.T_cam_base, result->T_right_base);
  const double target_mm =
      1000.0 *
      (result->T_flange_target.translation() - true_T_flange_target().translation()).norm();
  ASSERT_TRUE(result->baseline_left.solved);
  ASSERT_TRUE(result->baseline_right.solved);
  const PoseError shah_left =
      registration_error(truth.left.T_cam_base, result->baseline_left.T_cam_base);
  const PoseError shah_right =
      registration_error(truth.right.T_cam_base, result->baseline_right.T_cam_base);
  std::printf(
      "hand-eye: left %.3f mm %.4f deg, right %.3f mm %.4f deg, target %.3f mm %.4f deg; "
      "sigma base %.3f mm %.4f deg; Shah-Li left %.3f mm %.4f deg, right %.3f mm %.4f deg; "
      "rms %.3f / %.3f px\n",
      left.position_mm, left.rotation_deg, right.position_mm, right.rotation_deg, target_mm,
      angle_deg(result->T_flange_target, true_T_flange_target()), result->base_sigma.position_mm,
      result->base_sigma.rotation_deg, shah_left.position_mm, shah_left.rotation_deg,
      shah_right.position_mm, shah_right.rotation_deg, result->left.rms_px, result->right.rms_px);
  // The bound per eye, and better than the closed form on the same data.
  EXPECT_LT(left.position_mm, 0.5);
  EXPECT_LT(left.rotation_deg, 0.05);
  EXPECT_LT(right.position_mm, 0.5);
  EXPECT_LT(right.rotation_deg, 0.05);
  EXPECT_LT(left.position_mm, shah_left.position_mm);
  EXPECT_LT(right.position_mm, shah_right.position_mm);
  EXPECT_LT(target_mm, 0.5);
  // The residuals are the noise (0.1 px per axis: ~0.14 px) and the stated uncertainty is of
  // the order of the true error.
  EXPECT_LT(result->left.rms_px, 0.2);
  EXPECT_LT(result->right.rms_px, 0.2);
  EXPECT_GT(result->base_sigma.position_mm, 0.0);
  EXPECT_LT(left.position_mm, 4.0 * result->base_sigma.position_mm + 0.05);
  EXPECT_EQ(result->views_used, 30);
  EXPECT_EQ(result->views.size(), 30u);
  EXPECT_EQ(result->left.observations, 120);
}

// Without noise the closed-form baseline is exact: the eye-to-hand mapping onto OpenCV's
// robot-world/hand-eye problem is right, so the comparison above compares methods.
TEST_F(HandEyeRegistration, ShahLiBaselineIsExactWithoutNoise) {
  const HandEyeObservations observations = synthetic(*model, truth, 12, 0.0, 4);
  Result<HandEyeResult> result =
      register_hand_eye(*model, truth.left, truth.right, T_right_left_of(truth), observations);
  ASSERT_TRUE(result.ok()) << result.error().message;
  ASSERT_TRUE(result->baseline_left.solved);
  const PoseError shah =
      registration_error(truth.left.T_cam_base, result->baseline_left.T_cam_base);
  EXPECT_LT(shah.position_mm, 1e-3);
  EXPECT_LT(shah.rotation_deg, 1e-4);
  EXPECT_LT(
      (result->baseline_left.T_flange_target.translation() - true_T_flange_target().translation())
          .norm(),
      1e-6);
  EXPECT_LT(registration_error(truth.left.T_cam_base, result->T_left_base).position_mm, 1e-3);
}

// The answer of 20 views of which the solver dropped configuration 5 alone, and said so.
void expect_configuration_5_dropped(const Result<HandEyeResult>& result) {
  ASSERT_TRUE(result.ok()) << result.error().message;
  EXPECT_EQ(result->views_used, 19);
  ASSERT_FALSE(result->notes.empty());
  EXPECT_THAT(result->notes.front(), HasSubstr("configuration 5 dropped as an outlier: RMS "));
}

// A view a fraction of a pixel off among views that fit to hundredths (a target partly
// hidden behind a link in the simulator: 0.16-0.24 px RMS against a median view's 0.02-0.06
// px, issue 26 item 1) is dropped: the floor under the outlier limit is 0.1 px, not the 0.4 px
// that kept such views and moved the registration by 0.3-0.6 mm.
TEST_F(HandEyeRegistration, DropsAViewAFewTenthsOfAPixelOffAmongViewsThatFitToHundredths) {
  HandEyeObservations observations = synthetic(*model, truth, 20, 0.01, 3);
  for (std::vector<TargetPixel>* eye :
       {&observations.views[5].left, &observations.views[5].right}) {
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    for (const TargetPixel& p : *eye) centre += p.pixel / static_cast<double>(eye->size());
    for (TargetPixel& p : *eye) p.pixel += 0.2 * (p.pixel - centre).normalized();  // 0.2 px out
  }
  Result<HandEyeResult> result =
      register_hand_eye(*model, truth.left, truth.right, T_right_left_of(truth), observations);
  expect_configuration_5_dropped(result);
  ASSERT_TRUE(result.ok());
  HandEyeOptions old_floor;
  old_floor.outlier_min_px = 0.4;
  Result<HandEyeResult> kept = register_hand_eye(*model, truth.left, truth.right,
                                                 T_right_left_of(truth), observations, old_floor);
  ASSERT_TRUE(kept.ok()) << kept.error().message;
  EXPECT_EQ(kept->views_used, 20);
  EXPECT_LT(registration_error(truth.left.T_cam_base, result->T_left_base).position_mm,
            registration_error(truth.left.T_cam_base, kept->T_left_base).position_mm);
}

TEST_F(HandEyeRegistration, DropsAndNamesAnOutlierPose) {
  HandEyeObservations observations = synthetic(*model, truth, 20, 0.1, 3);
  for (TargetPixel& p : observations.views[5].left) p.pixel += Eigen::Vector2d(9.0, -6.0);
  Result<HandEyeResult> result =
      register_hand_eye(*model, truth.left, truth.right, T_right_left_of(truth), observations);
  expect_configuration_5_dropped(result);
  ASSERT_TRUE(result.ok());
  EXPECT_EQ(result->views.size(), 20u);
  EXPECT_TRUE(result->views.back().dropped);
  const PoseError left = registration_error(truth.left.T_cam_base, result->T_left_base);
  EXPECT_LT(left.position_mm, 1.0);
}

TEST_F(HandEyeRegistration, OneEyeOnlyStillRegistersBothThroughTheStereoConstraint) {
  HandEyeObservations observations = synthetic(*model, truth, 20, 0.1, 5);
  for (HandEyeView& v : observations.views) v.right.clear();
  Result<HandEyeResult> result =
      register_hand_eye(*model, truth.left, truth.right, T_right_left_of(truth), observations);
  ASSERT_TRUE(result.ok()) << result.error().message;
  EXPECT_FALSE(result->baseline_right.solved);
  EXPECT_THAT(result->notes.back(), HasSubstr("right eye: no closed-form baseline (0 poses"));
  EXPECT_LT(registration_error(truth.right.T_cam_base, result->T_right_base).position_mm, 1.5);
}

TEST_F(HandEyeRegistration, RefusesRotationsAboutOneAxis) {
  // Only joint 1 moves: every flange rotation is about the base's z axis.
  HandEyeObservations observations = synthetic(*model, truth, 1, 0.0, 9);
  const Eigen::VectorXd q0 = observations.views[0].q;
  HandEyeObservations turning;
  turning.target_points = marker_points();
  core::KinematicsData data(*model);
  for (int k = 0; k < 8; ++k) {
    HandEyeView view;
    view.name = "pose " + std::to_string(k);
    view.q = q0;
    view.q[0] += 0.02 * (k - 4);
    core::forward_kinematics(*model, data, view.q);
    for (std::size_t i = 0; i < marker_points().size(); ++i) {
      const Eigen::Vector3d p =
          data.T_base_link.back() * true_T_flange_target() * marker_points()[i];
      view.left.push_back({static_cast<int>(i), *truth.left.project(p)});
    }
    turning.views.push_back(view);
  }
  Result<HandEyeResult> result =
      register_hand_eye(*model, truth.left, truth.right, T_right_left_of(truth), turning);
  ASSERT_FALSE(result.ok());
  EXPECT_THAT(result.error().message,
              HasSubstr("every rotation between the poses turns the flange about one axis"));
  EXPECT_THAT(result.error().message, HasSubstr("[0.00, 0.00, 1.00] in the base frame"));
  EXPECT_THAT(result.error().message, HasSubstr("turn the wrist about another axis"));
}

TEST_F(HandEyeRegistration, BadInputIsNamed) {
  HandEyeObservations observations = synthetic(*model, truth, 6, 0.1, 2);
  auto message = [&](const HandEyeObservations& o, const HandEyeOptions& options = {}) {
    Result<HandEyeResult> r =
        register_hand_eye(*model, truth.left, truth.right, T_right_left_of(truth), o, options);
    return r.ok() ? std::string("ok") : r.error().message;
  };
  HandEyeObservations few = observations;
  few.views.resize(3);
  EXPECT_THAT(message(few), HasSubstr("3 usable poses (the target seen by at least one eye), at "
                                      "least 4 are needed"));
  HandEyeObservations unseen = observations;
  unseen.views[1].left.clear();
  unseen.views[1].right.clear();
  unseen.views.resize(4);
  EXPECT_THAT(message(unseen), HasSubstr("3 usable poses"));
  HandEyeObservations bad_index = observations;
  bad_index.views[2].right[1].point = 4;
  EXPECT_EQ(message(bad_index),
            "configuration 2: right[1]: point 4 is not one of the target's 4 points");
  HandEyeObservations nan = observations;
  nan.views[0].left[0].pixel.x() = std::nan("");
  EXPECT_EQ(message(nan), "configuration 0: left[0]: pixel is not finite");
  HandEyeObservations short_q = observations;
  short_q.views[3].q.resize(5);
  EXPECT_THAT(message(short_q), HasSubstr("configuration 3: 5 joint values, but robot"));
  HandEyeOptions options;
  options.loss_scale_px = -1;
  EXPECT_EQ(message(observations, options),
            "hand-eye option loss_scale_px = -1 must be in (0, 100] px");
  HandEyeOptions strict;
  strict.max_sigma_mm = 1e-6;
  EXPECT_THAT(message(observations, strict),
              HasSubstr("the registration is poorly conditioned: the base is known only to"));
}

}  // namespace
}  // namespace telear::vision
