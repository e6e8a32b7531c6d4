// camera_info -> telear's stereo calibration (drivers/ros1/camera_info_calibration.hpp): each
// lens model, the baseline of a rectified pair, and what is refused, by its message.
#include "drivers/ros1/camera_info_calibration.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "telear/vision/camera_file.hpp"

namespace telear::drivers::ros1 {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

const TopicImageSize kLeftImage{"/stereo/left/image_raw", 640, 480};
const TopicImageSize kRightImage{"/stereo/right/image_raw", 640, 480};

CameraInfoFields info(const std::string& topic, const std::string& model, std::vector<double> d,
                      double tx = 0.0) {
  CameraInfoFields f;
  f.topic = topic;
  f.frame_id = "optical";
  f.width = 640;
  f.height = 480;
  f.distortion_model = model;
  f.D = std::move(d);
  f.K = {500.0, 0.0, 320.5, 0.0, 501.0, 239.5, 0.0, 0.0, 1.0};
  f.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  f.P = {500.0, 0.0, 320.5, tx, 0.0, 501.0, 239.5, 0.0, 0.0, 0.0, 1.0, 0.0};
  return f;
}

CameraInfoFields left_info(const std::string& model, std::vector<double> d) {
  return info("/stereo/left/camera_info", model, std::move(d));
}
CameraInfoFields right_info(const std::string& model, std::vector<double> d, double tx = 0.0) {
  return info("/stereo/right/camera_info", model, std::move(d), tx);
}

vision::CameraFile read_back(const CameraInfoCalibration& calibration) {
  auto file = vision::parse_camera_yaml(calibration.yaml, "test");
  EXPECT_TRUE(file) << file.error().message;
  return *file;
}

std::string error_of(const CameraInfoFields& left, const CameraInfoFields& right) {
  auto calibration = calibration_from_camera_info(left, right, kLeftImage, kRightImage);
  return calibration ? std::string("no error") : calibration.error().message;
}

TEST(CameraInfoCalibration, APlumbBobRectifiedPairGivesIntrinsicsAndBaseline) {
  auto calibration = calibration_from_camera_info(
      left_info("plumb_bob", {-0.2, 0.03, 0.001, -0.002, 0.004}),
      right_info("plumb_bob", {-0.1, 0.02, 0.0, 0.0, 0.0}, -500.0 * 0.12), kLeftImage, kRightImage);
  ASSERT_TRUE(calibration) << calibration.error().message;
  EXPECT_TRUE(calibration->warnings.empty());
  const vision::CameraFile file = read_back(*calibration);
  ASSERT_TRUE(file.is_stereo());
  EXPECT_EQ(file.left.fx, 500.0);
  EXPECT_EQ(file.left.fy, 501.0);
  EXPECT_EQ(file.left.cx, 320.5);
  EXPECT_THAT(file.left.kc.coefficients(), ElementsAre(-0.2, 0.03, 0.001, -0.002, 0.004));
  EXPECT_EQ(file.right->kc.model, vision::DistortionModel::plumb_bob);
  ASSERT_TRUE(file.T_right_left);
  EXPECT_TRUE(file.T_right_left->linear().isIdentity(1e-15));
  EXPECT_NEAR(file.T_right_left->translation().x(), -0.12, 1e-15);
  EXPECT_EQ(file.T_right_left->translation().tail<2>().norm(), 0.0);
  EXPECT_FALSE(file.left_has_pose);  // calibrated, not registered to the robot
  EXPECT_EQ(file.left_name, "optical");
}

TEST(CameraInfoCalibration, RationalAndEquidistantLensesKeepTheirModel) {
  auto calibration = calibration_from_camera_info(
      left_info("rational_polynomial", {-0.3, 0.1, 0.001, 0.002, 0.01, 0.05, 0.004, 0.0005}),
      right_info("equidistant", {0.08, -0.01, 0.003, -0.0004}), kLeftImage, kRightImage);
  ASSERT_TRUE(calibration) << calibration.error().message;
  const vision::CameraFile file = read_back(*calibration);
  EXPECT_EQ(file.left.kc.model, vision::DistortionModel::rational_polynomial);
  EXPECT_THAT(file.left.kc.coefficients(),
              ElementsAre(-0.3, 0.1, 0.001, 0.002, 0.01, 0.05, 0.004, 0.0005));
  EXPECT_EQ(file.right->kc.model, vision::DistortionModel::equidistant);
  EXPECT_THAT(file.right->kc.coefficients(), ElementsAre(0.08, -0.01, 0.003, -0.0004));
  // Two P = [K | 0]: no pair is stated, so no pose between the cameras.
  EXPECT_FALSE(file.T_right_left);
  EXPECT_THAT(calibration->warnings,
              ElementsAre(HasSubstr("camera_info on /stereo/right/camera_info: P has Tx = Ty = "
                                    "0, so the cameras are not stated as a rectified pair")));
}

TEST(CameraInfoCalibration, LongerDVectorsMayOnlyAddZeros) {
  auto calibration = calibration_from_camera_info(
      left_info("plumb_bob", {-0.2, 0.03, 0.0, 0.0, 0.004, 0.0, 0.0, 0.0}), right_info("", {}),
      kLeftImage, kRightImage);
  ASSERT_TRUE(calibration) << calibration.error().message;
  const vision::CameraFile file = read_back(*calibration);
  EXPECT_EQ(file.left.kc.coefficients().size(), 5u);
  EXPECT_TRUE(file.right->kc.is_zero());  // no model and no D: no distortion

  EXPECT_EQ(error_of(left_info("plumb_bob", {-0.2, 0.03, 0.0, 0.0, 0.004, 0.1, 0.0, 0.0}),
                     right_info("plumb_bob", {})),
            "camera_info on /stereo/left/camera_info: D: coefficient 5 is 0.10000000000000001; "
            "plumb_bob has 5 (a lens with k4..k6 is rational_polynomial; thin-prism and tilt "
            "terms are not modelled)");
  EXPECT_EQ(
      error_of(left_info("plumb_bob", {}), right_info("equidistant", {0.1, 0.0, 0.0, 0.0, 0.0})),
      "camera_info on /stereo/right/camera_info: D: equidistant takes 4 distortion "
      "coefficients, got 5");
  EXPECT_EQ(error_of(left_info("", {0.1}), right_info("plumb_bob", {})),
            "camera_info on /stereo/left/camera_info: distortion_model is empty but D is not "
            "zero (name the model: plumb_bob, rational_polynomial or equidistant)");
  EXPECT_EQ(error_of(left_info("plumb_bob", {}), right_info("kannala_brandt", {0, 0, 0, 0})),
            "camera_info on /stereo/right/camera_info: distortion_model: unknown distortion "
            "model 'kannala_brandt' (expected plumb_bob, rational_polynomial or equidistant)");
}

TEST(CameraInfoCalibration, BinningRegionsOfInterestAndOtherSizesAreRefused) {
  CameraInfoFields binned = left_info("plumb_bob", {});
  binned.binning_x = binned.binning_y = 2;
  EXPECT_THAT(error_of(binned, right_info("plumb_bob", {})),
              HasSubstr("camera_info on /stereo/left/camera_info: binning 2x2 is not supported "
                        "(K is the full sensor's, not the image's)"));
  CameraInfoFields cropped = right_info("plumb_bob", {});
  cropped.roi_x_offset = 10;
  cropped.roi_width = 320;
  cropped.roi_height = 240;
  EXPECT_THAT(error_of(left_info("plumb_bob", {}), cropped),
              HasSubstr("camera_info on /stereo/right/camera_info: a region of interest "
                        "(320x240 at 10, 0) is not supported"));
  CameraInfoFields full_roi = right_info("plumb_bob", {});  // a ROI of the whole image is none
  full_roi.roi_width = 640;
  full_roi.roi_height = 480;
  EXPECT_EQ(error_of(left_info("plumb_bob", {}), full_roi), "no error");
  CameraInfoFields other_size = left_info("plumb_bob", {});
  other_size.width = 1280;
  other_size.height = 960;
  EXPECT_EQ(error_of(other_size, right_info("plumb_bob", {})),
            "camera_info on /stereo/left/camera_info: is for 1280x960 images, but those on "
            "/stereo/left/image_raw are 640x480");
  CameraInfoFields skewed_row = left_info("plumb_bob", {});
  skewed_row.K[3] = 0.5;
  EXPECT_EQ(error_of(skewed_row, right_info("plumb_bob", {})),
            "camera_info on /stereo/left/camera_info: K must be [fx s cx; 0 fy cy; 0 0 1]");
}

TEST(CameraInfoCalibration, AnUncalibratedCameraGivesNoCalibrationAndAWarning) {
  CameraInfoFields zero = left_info("plumb_bob", {});
  zero.K = {};
  auto calibration =
      calibration_from_camera_info(zero, right_info("plumb_bob", {}), kLeftImage, kRightImage);
  ASSERT_TRUE(calibration) << calibration.error().message;
  EXPECT_TRUE(calibration->yaml.empty());
  EXPECT_THAT(calibration->warnings,
              ElementsAre("camera_info on /stereo/left/camera_info: uncalibrated (K is zero, or "
                          "the placeholder fx = fy = 1): GetCameraInfo serves no calibration; "
                          "calibrate the camera or give --calibration"));
  CameraInfoFields placeholder = right_info("plumb_bob", {});  // image_publisher's
  placeholder.K = {1, 0, 320, 0, 1, 240, 0, 0, 1};
  calibration = calibration_from_camera_info(left_info("plumb_bob", {}), placeholder, kLeftImage,
                                             kRightImage);
  ASSERT_TRUE(calibration) << calibration.error().message;
  EXPECT_TRUE(calibration->yaml.empty());
}

TEST(CameraInfoCalibration, AMalformedRectificationOnlyCostsThePose) {
  CameraInfoFields bad_r = right_info("plumb_bob", {}, -60.0);
  bad_r.R = {2, 0, 0, 0, 1, 0, 0, 0, 1};
  auto calibration =
      calibration_from_camera_info(left_info("plumb_bob", {}), bad_r, kLeftImage, kRightImage);
  ASSERT_TRUE(calibration) << calibration.error().message;
  EXPECT_FALSE(read_back(*calibration).T_right_left);
  EXPECT_THAT(calibration->warnings,
              ElementsAre("camera_info on /stereo/right/camera_info: R is not a rotation: no "
                          "rectification, so GetCameraInfo serves no pose between the cameras"));
}

}  // namespace
}  // namespace telear::drivers::ros1
