// Registration on synthetic observations: the shipped stereo rig is the truth, the PUMA 560
// moves an ArUco-sized marker on its flange through random in-limit configurations, and the
// true cameras project the corners (with distortion) plus 0.1 px Gaussian noise.

#include "telear/vision/registration.hpp"

#include <gtest/gtest.h>

#include <random>

#include "synthetic_observations.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/vision/camera_file.hpp"
#include "telear/vision/observations_file.hpp"
#include "telear/vision/overlay_accuracy.hpp"
#include "test_util/test_util.hpp"

namespace telear::vision {
namespace {

using test::T_right_left_of;

// Camera models with the pose removed: what the registration starts from.
StereoCameraModel unregistered(StereoCameraModel rig) {
  rig.left.T_cam_base = Eigen::Isometry3d::Identity();
  rig.right.T_cam_base = Eigen::Isometry3d::Identity();
  return rig;
}

TEST(Registration, RecoversTheTrueBasePoseFromMarkerCorners) {
  const core::RobotModelPtr model = test::puma560();
  const StereoCameraModel truth = test::shipped_stereo_cameras();
  const RegistrationObservations observations =
      test::synthetic_observations(*model, truth, test::flange_marker_corners(), 15, 0.1, 7);
  const StereoCameraModel start = unregistered(truth);
  Result<RegistrationResult> result =
      register_stereo(*model, start.left, start.right, T_right_left_of(truth), observations);
  ASSERT_TRUE(result.ok()) << result.error().message;
  const PoseError left = registration_error(truth.left.T_cam_base, result->T_left_base);
  const PoseError right = registration_error(truth.right.T_cam_base, result->T_right_base);
  std::printf(
      "marker: left %.3f mm %.4f deg, right %.3f mm %.4f deg; rms %.3f / %.3f px (%d "
      "+ %d points, %d iterations)\n",
      left.position_mm, left.rotation_deg, right.position_mm, right.rotation_deg,
      result->left.rms_px, result->right.rms_px, result->left.observations,
      result->right.observations, result->iterations);
  EXPECT_LT(left.position_mm, 1.0);
  EXPECT_LT(left.rotation_deg, 0.1);
  EXPECT_LT(right.position_mm, 1.0);
  EXPECT_LT(right.rotation_deg, 0.1);
  EXPECT_EQ(result->left.observations, 60);
  EXPECT_EQ(result->right.observations, 60);
  EXPECT_EQ(result->configurations_used, 15);
  // The residual RMS of a correct fit is the noise level (0.1 px per axis: ~0.14 px).
  EXPECT_LT(result->left.rms_px, 0.2);
  EXPECT_LT(result->right.rms_px, 0.2);
}

TEST(Registration, EstimatedIntrinsicsStillMeetTheTargets) {
  // Intrinsics off by what a good calibration leaves (fx, fy 0.1 %, cc 0.5 px, k1 0.5 %).
  const core::RobotModelPtr model = test::puma560();
  const StereoCameraModel truth = test::shipped_stereo_cameras();
  const RegistrationObservations observations =
      test::synthetic_observations(*model, truth, test::flange_marker_corners(), 20, 0.1, 11);
  StereoCameraModel estimate = unregistered(truth);
  for (CameraModel* camera : {&estimate.left, &estimate.right}) {
    camera->fx *= 1.001;
    camera->fy *= 0.999;
    camera->cx += 0.5;
    camera->cy -= 0.5;
    camera->kc.k1 *= 1.005;
  }
  Result<RegistrationResult> result =
      register_stereo(*model, estimate.left, estimate.right, T_right_left_of(truth), observations);
  ASSERT_TRUE(result.ok()) << result.error().message;
  const PoseError left = registration_error(truth.left.T_cam_base, result->T_left_base);
  const PoseError right = registration_error(truth.right.T_cam_base, result->T_right_base);
  std::printf(
      "estimated intrinsics: left %.3f mm %.4f deg, right %.3f mm %.4f deg; rms %.3f / "
      "%.3f px\n",
      left.position_mm, left.rotation_deg, right.position_mm, right.rotation_deg,
      result->left.rms_px, result->right.rms_px);
  EXPECT_LT(left.rotation_deg, 0.1);
  EXPECT_LT(right.rotation_deg, 0.1);
  EXPECT_LT(left.position_mm, 5.0);  // depth absorbs the focal length error (0.1 % of 2.5 m)
}

TEST(Registration, OperatorClickedToolTipsGiveTheSamePose) {
  const core::RobotModelPtr model = test::puma560();
  const StereoCameraModel truth = test::shipped_stereo_cameras();
  // One point per configuration: the tool centre point (here the flange origin offset).
  const RegistrationObservations marker = test::synthetic_observations(
      *model, truth, {model->T_flange_tool().translation()}, 12, 0.3, 5);
  std::vector<ToolTipClick> clicks;
  for (const ObservedConfiguration& c : marker.configurations) {
    clicks.push_back({c.q, c.left_pixels[0], c.right_pixels[0]});
  }
  clicks[3].right.reset();  // not clicked in one eye
  const RegistrationObservations observations = tool_tip_observations(*model, clicks);
  ASSERT_EQ(observations.point_in_flange.size(), 1u);
  const StereoCameraModel start = unregistered(truth);
  Result<RegistrationResult> result =
      register_stereo(*model, start.left, start.right, T_right_left_of(truth), observations);
  ASSERT_TRUE(result.ok()) << result.error().message;
  const PoseError left = registration_error(truth.left.T_cam_base, result->T_left_base);
  std::printf("tool tip (0.3 px clicks): left %.3f mm %.4f deg\n", left.position_mm,
              left.rotation_deg);
  EXPECT_EQ(result->left.observations, 12);
  EXPECT_EQ(result->right.observations, 11);
  EXPECT_LT(left.position_mm, 5.0);
  EXPECT_LT(left.rotation_deg, 0.2);
}

TEST(Registration, TooFewConfigurationsSaysWhich) {
  const core::RobotModelPtr model = test::puma560();
  const StereoCameraModel truth = test::shipped_stereo_cameras();
  RegistrationObservations observations =
      test::synthetic_observations(*model, truth, test::flange_marker_corners(), 3, 0.1, 3);
  observations.configurations[2] = observations.configurations[0];  // a repeat
  Result<RegistrationResult> result =
      register_stereo(*model, truth.left, truth.right, T_right_left_of(truth), observations);
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.error().message.find("too few configurations: 2 distinct usable of 3"),
            std::string::npos)
      << result.error().message;
  EXPECT_NE(result.error().message.find("configuration 2 (flange within 10 mm"), std::string::npos)
      << result.error().message;

  observations.configurations[2].left_pixels.clear();
  observations.configurations[2].right_pixels.clear();
  result = register_stereo(*model, truth.left, truth.right, T_right_left_of(truth), observations);
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.error().message.find("configuration 2 (seen by neither eye)"), std::string::npos)
      << result.error().message;
}

TEST(Registration, CollinearToolTipsAreDegenerate) {
  const core::RobotModelPtr model = test::puma560();
  const StereoCameraModel truth = test::shipped_stereo_cameras();
  // One point fixed to the flange but lying on joint 1's axis (at q = 0), and only joint 1
  // moving: the flange origins are distinct, the observed point never moves.
  RegistrationObservations observations;
  core::KinematicsData data(*model);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model->dof());
  core::forward_kinematics(*model, data, q);
  const Eigen::Vector3d on_axis = data.T_base_link.back().inverse() * Eigen::Vector3d(0, 0, 0.3);
  observations.point_in_flange = {on_axis};
  for (double q1 : {-0.5, 0.0, 0.5, 1.0}) {
    ObservedConfiguration c;
    c.q = q;
    c.q[0] = q1;
    c.left_pixels = {Eigen::Vector2d(300, 200)};
    c.right_pixels = {Eigen::Vector2d(290, 200)};
    observations.configurations.push_back(c);
  }
  Result<RegistrationResult> result =
      register_stereo(*model, truth.left, truth.right, T_right_left_of(truth), observations);
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.error().message.find("lie on one line"), std::string::npos)
      << result.error().message;
}

TEST(Registration, BadInputNamesTheProblem) {
  const core::RobotModelPtr model = test::puma560();
  const StereoCameraModel truth = test::shipped_stereo_cameras();
  const RegistrationObservations good =
      test::synthetic_observations(*model, truth, test::flange_marker_corners(), 4, 0.1, 9);

  RegistrationObservations unequal = good;
  unequal.configurations[1].right_pixels.pop_back();
  Result<RegistrationResult> result =
      register_stereo(*model, truth.left, truth.right, T_right_left_of(truth), unequal);
  ASSERT_FALSE(result.ok());
  EXPECT_NE(
      result.error().message.find("configurations[1].right: 3 pixels, but point_in_flange has 4"),
      std::string::npos)
      << result.error().message;

  RegistrationObservations nan = good;
  nan.configurations[2].left_pixels[1].x() = std::nan("");
  result = register_stereo(*model, truth.left, truth.right, T_right_left_of(truth), nan);
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.error().message.find("configurations[2].left[1]: not finite"), std::string::npos)
      << result.error().message;

  RegistrationObservations short_q = good;
  for (auto& c : short_q.configurations) c.q.conservativeResize(5);
  result = register_stereo(*model, truth.left, truth.right, T_right_left_of(truth), short_q);
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.error().message.find("5 joint values, but robot 'puma560' has 6 joints"),
            std::string::npos)
      << result.error().message;
}

TEST(ObservationsFile, RoundTripsAndReportsMalformedInput) {
  const core::RobotModelPtr model = test::puma560();
  const StereoCameraModel truth = test::shipped_stereo_cameras();
  RegistrationObservations observations =
      test::synthetic_observations(*model, truth, test::flange_marker_corners(), 3, 0.1, 13);
  observations.configurations[1].right_pixels.clear();
  Result<RegistrationObservations> parsed =
      parse_observations_yaml(observations_yaml(observations), "mem");
  ASSERT_TRUE(parsed.ok()) << parsed.error().message;
  ASSERT_EQ(parsed->configurations.size(), 3u);
  EXPECT_EQ(parsed->robot, "puma560");
  EXPECT_TRUE(parsed->configurations[1].right_pixels.empty());
  EXPECT_EQ(parsed->configurations[2].q, observations.configurations[2].q);
  EXPECT_EQ(parsed->configurations[0].left_pixels[3],
            observations.configurations[0].left_pixels[3]);

  auto message = [](const std::string& text) {
    Result<RegistrationObservations> r = parse_observations_yaml(text, "obs.yaml");
    return r.ok() ? std::string("(accepted)") : r.error().message;
  };
  EXPECT_NE(message("[1, 2").find("observations 'obs.yaml': not valid YAML"), std::string::npos);
  EXPECT_NE(message("point_in_flange: []").find("telear_observations: missing"), std::string::npos);
  EXPECT_NE(message("telear_observations: 2").find("unsupported version 2"), std::string::npos);
  const std::string head = "telear_observations: 1\npoint_in_flange: [[0, 0, 0.1], [0, 0.1, 0]]\n";
  EXPECT_NE(message(head).find("configurations: missing"), std::string::npos);
  EXPECT_NE(message(head + "configurations:\n  - left: []\n").find("configurations[0].q: missing"),
            std::string::npos);
  EXPECT_NE(message(head + "configurations:\n  - q: [0, x]\n")
                .find("configurations[0].q[1]: must be a number, got 'x'"),
            std::string::npos);
  EXPECT_NE(message(head + "configurations:\n  - q: [0, 0]\n    left: [[1, 2, 3], [1, 2]]\n")
                .find("configurations[0].left[0]: a pixel is [u, v], got 3 numbers"),
            std::string::npos);
  EXPECT_NE(message(head + "configurations:\n  - q: [0, 0]\n    left: [[1, 2]]\n")
                .find("configurations[0].left: 1 pixels, but point_in_flange has 2"),
            std::string::npos);
  EXPECT_NE(message(head + "configurations:\n  - q: [0, .nan]\n").find("must be finite"),
            std::string::npos);
  EXPECT_NE(message("telear_observations: 1\npoint_in_flange: [[0, 0]]\nconfigurations: []\n")
                .find("point_in_flange[0]: a point is [x, y, z], got 2 numbers"),
            std::string::npos);
  Result<RegistrationObservations> missing = load_observations_file("/nonexistent/obs.yaml");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find("cannot open observations file '/nonexistent/obs.yaml'"),
            std::string::npos);
}

}  // namespace
}  // namespace telear::vision
