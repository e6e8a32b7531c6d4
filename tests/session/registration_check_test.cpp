#include "telear/session/registration_check.hpp"

#include <gtest/gtest.h>

#include <iostream>

#include "synthetic_marker.hpp"
#include "telear/core/angles.hpp"
#include "telear/core/kinematics.hpp"
#include "test_util/test_util.hpp"

namespace telear::session {
namespace {

// A camera 1.6 m from the flange looking at it, and a 0.1 m marker fixed to the flange that
// faces the camera at q (corners in cv::aruco order as the camera sees them).
class RegistrationCheckTest : public ::testing::Test {
 protected:
  void SetUp() override {
    model_ = test::puma560();
    q_ = Eigen::VectorXd(6);
    q_ << 0.2, 0.4, -0.9, 0.1, 0.6, 0.3;
    core::KinematicsData data(*model_);
    core::forward_kinematics(*model_, data, q_);
    const Eigen::Isometry3d T_base_flange = data.T_base_link.back();
    const Eigen::Vector3d centre = T_base_flange.translation();
    camera_ = vision::look_at_camera(640, 480, core::radians_from_degrees(50.0),
                                     centre + Eigen::Vector3d(1.4, 0.5, 0.6), centre,
                                     Eigen::Vector3d::UnitZ());
    const Eigen::Matrix3d R_base_cam = camera_.T_cam_base.linear().transpose();
    const double h = 0.05;
    const std::array<Eigen::Vector2d, 4> xy = {Eigen::Vector2d(-h, -h), Eigen::Vector2d(h, -h),
                                               Eigen::Vector2d(h, h), Eigen::Vector2d(-h, h)};
    marker_.id = 2;
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d p_base = centre + R_base_cam * Eigen::Vector3d(xy[k].x(), xy[k].y(), 0);
      marker_.corners_flange[k] = T_base_flange.inverse() * p_base;
      truth_[k] = *camera_.project(p_base);
    }
    test::SyntheticMarkerOptions options;
    options.id = 2;
    options.noise_sigma = 1.0;
    image_ = test::synthetic_marker_image(640, 480, truth_, options);
  }
  core::RobotModelPtr model_;
  Eigen::VectorXd q_;
  vision::CameraModel camera_;
  GripperMarker marker_;
  std::array<Eigen::Vector2d, 4> truth_;
  cv::Mat image_;
};

TEST_F(RegistrationCheckTest, ResidualIsSubPixelWhenTheCalibrationHolds) {
  const RegistrationCheck check(model_, {camera_, camera_}, marker_);
  const auto predicted = check.predict(camera_, q_);
  ASSERT_EQ(predicted.size(), 4u);
  for (int k = 0; k < 4; ++k) EXPECT_LT((predicted[k] - truth_[k]).norm(), 1e-9);
  const EyeResidual r = check.check_eye(image_, camera_, q_);
  ASSERT_TRUE(r.valid()) << r.message;
  EXPECT_TRUE(r.message.empty());
  EXPECT_LT(r.rms_px, 0.15);
  EXPECT_LE(r.rms_px, r.max_px);
}

TEST_F(RegistrationCheckTest, ABumpedCameraOrWrongJointsShowInThePixels) {
  // The camera turned by 0.3 deg since registration: the model's prediction moves ~2.7 px.
  vision::CameraModel bumped = camera_;
  bumped.T_cam_base.prerotate(
      Eigen::AngleAxisd(core::radians_from_degrees(0.3), Eigen::Vector3d::UnitY()));
  const RegistrationCheck check(model_, {bumped, bumped}, marker_);
  const EyeResidual r = check.check_eye(image_, bumped, q_);
  ASSERT_TRUE(r.valid()) << r.message;
  double expected_rms = 0, expected_max = 0;
  corner_residual({truth_.begin(), truth_.end()}, check.predict(bumped, q_), expected_rms,
                  expected_max);
  std::cout << "camera turned 0.3 deg: residual " << r.rms_px << " px rms (model: " << expected_rms
            << " px)\n";
  EXPECT_GT(expected_rms, 2.0);
  EXPECT_NEAR(r.rms_px, expected_rms, 0.15);
  // Joints off by 0.01 rad at the waist move the prediction too.
  Eigen::VectorXd q = q_;
  q[0] += 0.01;
  const EyeResidual joint =
      RegistrationCheck(model_, {camera_, camera_}, marker_).check_eye(image_, camera_, q);
  ASSERT_TRUE(joint.valid());
  EXPECT_GT(joint.rms_px, 1.0);
}

TEST_F(RegistrationCheckTest, SaysWhyThereIsNoResidual) {
  const RegistrationCheck check(model_, {camera_, camera_}, marker_);
  const cv::Mat blank(480, 640, CV_8UC3, cv::Scalar(120, 120, 120));
  const StereoResidual both = check.check(image_, blank, q_);
  EXPECT_TRUE(both.left.valid());
  EXPECT_FALSE(both.right.valid());
  EXPECT_TRUE(both.right.predicted);
  EXPECT_EQ(both.right.message, "marker 2 not detected in the image");
  // A camera looking the other way: the model puts the marker behind it.
  vision::CameraModel away = camera_;
  away.T_cam_base.prerotate(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitY()));
  const EyeResidual behind = check.check_eye(image_, away, q_);
  EXPECT_FALSE(behind.valid());
  EXPECT_EQ(behind.message, "the model puts marker 2 behind the camera");
}

TEST(CornerResidual, RmsAndMax) {
  double rms = 0, max = 0;
  corner_residual({{0, 0}, {1, 1}}, {{3, 4}, {1, 1}}, rms, max);
  EXPECT_DOUBLE_EQ(max, 5.0);
  EXPECT_DOUBLE_EQ(rms, std::sqrt(12.5));
}

}  // namespace
}  // namespace telear::session
