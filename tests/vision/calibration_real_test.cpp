// Real images: OpenCV's stereo chessboard set from Debian's opencv-doc package (13 pairs,
// 640x480, 9x6 inner corners). telear's stereo calibration must reach the RMS of OpenCV's
// reference procedure, the one of its sample stereo_calib.cpp, run here on the same images.
// Square size 1 (the sample's default): lengths come out in squares.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "telear/vision/calibration_images.hpp"
#include "telear/vision/image_file.hpp"
#include "telear/vision/stereo_calibration.hpp"

namespace telear::vision {
namespace {

std::string samples_dir() {
  const char* dir = std::getenv("TELEAR_OPENCV_SAMPLES");
  return dir ? dir : "/usr/share/doc/opencv-doc/examples/data";
}

// left01 ... left14 without 10, as stereo_calib.xml lists them.
std::vector<std::string> sample_images(const std::string& side) {
  std::vector<std::string> paths;
  for (int i : {1, 2, 3, 4, 5, 6, 7, 8, 9, 11, 12, 13, 14}) {
    char name[32];
    std::snprintf(name, sizeof name, "/%s%02d.jpg", side.c_str(), i);
    paths.push_back(samples_dir() + name);
  }
  return paths;
}

bool samples_present() {
  for (const std::string& p : sample_images("left")) {
    if (!std::filesystem::exists(p)) return false;
  }
  return true;
}

struct Reference {
  double rms = 0.0;
  cv::Mat T;
  std::vector<StereoPatternView> views;  // the sample's corners
};

// OpenCV's samples/cpp/stereo_calib.cpp, calibration part, verbatim in substance: corners
// by findChessboardCorners (retried at 2x), cornerSubPix 11x11; initCameraMatrix2D; then
// stereoCalibrate with the sample's flags and criteria.
Reference opencv_reference(const std::vector<std::size_t>& pairs) {
  const cv::Size board(9, 6);
  const std::vector<std::string> left = sample_images("left"), right = sample_images("right");
  std::vector<std::vector<cv::Point2f>> points[2];
  std::vector<std::vector<cv::Point3f>> object;
  cv::Size size;
  Reference reference;
  for (std::size_t i : pairs) {
    std::vector<cv::Point2f> corners[2];
    bool both = true;
    for (int k = 0; k < 2 && both; ++k) {
      auto read = read_image_file(k == 0 ? left[i] : right[i], ImageFileMode::kGrey);
      EXPECT_TRUE(read) << read.error().message;
      const cv::Mat image = read ? *read : cv::Mat();
      size = image.size();
      bool found = false;
      for (int scale = 1; scale <= 2 && !found; ++scale) {
        cv::Mat scaled = image;
        if (scale > 1) cv::resize(image, scaled, cv::Size(), scale, scale, cv::INTER_LINEAR_EXACT);
        found = cv::findChessboardCorners(
            scaled, board, corners[k], cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE);
        if (found && scale > 1) {
          for (cv::Point2f& p : corners[k]) p *= 1.0f / static_cast<float>(scale);
        }
      }
      both = found;
      if (found) {
        cv::cornerSubPix(
            image, corners[k], cv::Size(11, 11), cv::Size(-1, -1),
            cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 30, 0.01));
      }
    }
    if (!both) continue;
    points[0].push_back(corners[0]);
    points[1].push_back(corners[1]);
    reference.views.push_back({left[i], right[i], corners[0], corners[1]});
    std::vector<cv::Point3f> o;
    for (int r = 0; r < board.height; ++r) {
      for (int c = 0; c < board.width; ++c)
        o.emplace_back(static_cast<float>(c), static_cast<float>(r), 0.0f);
    }
    object.push_back(o);
  }
  cv::Mat K[2], D[2], R, E, F;
  K[0] = cv::initCameraMatrix2D(object, points[0], size, 0);
  K[1] = cv::initCameraMatrix2D(object, points[1], size, 0);
  reference.rms = cv::stereoCalibrate(
      object, points[0], points[1], K[0], D[0], K[1], D[1], size, R, reference.T, E, F,
      cv::CALIB_FIX_ASPECT_RATIO + cv::CALIB_ZERO_TANGENT_DIST + cv::CALIB_USE_INTRINSIC_GUESS +
          cv::CALIB_SAME_FOCAL_LENGTH + cv::CALIB_RATIONAL_MODEL + cv::CALIB_FIX_K3 +
          cv::CALIB_FIX_K4 + cv::CALIB_FIX_K5,
      cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-5));
  return reference;
}

// The reference on all 13 pairs, computed once per test run.
const Reference& reference_on_all_pairs() {
  static const Reference reference = [] {
    std::vector<std::size_t> all(13);
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
    return opencv_reference(all);
  }();
  return reference;
}

class RealStereoSet : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(samples_present())
        << "OpenCV's sample images are missing from " << samples_dir()
        << ": install Debian's opencv-doc package (scripts/install-deps.sh does) or point "
           "TELEAR_OPENCV_SAMPLES at a folder with left01.jpg ... right14.jpg";
  }
};

TEST_F(RealStereoSet, TelearReachesOpenCVsReferenceRms) {
  const CalibrationPattern pattern = *parse_calibration_pattern("chessboard:9x6:1");
  const auto detected =
      detect_in_image_pairs(sample_images("left"), sample_images("right"), pattern);
  ASSERT_TRUE(detected.ok()) << detected.error().message;
  EXPECT_EQ(detected->views.size(), 13u);
  EXPECT_TRUE(detected->rejected.empty());
  EXPECT_EQ(detected->image_size, cv::Size(640, 480));

  const auto telear = calibrate_stereo(pattern, detected->views, detected->image_size);
  ASSERT_TRUE(telear.ok()) << telear.error().message;

  const Reference& reference = reference_on_all_pairs();
  ASSERT_EQ(reference.views.size(), 13u);

  std::printf(
      "OpenCV stereo set, 13 pairs: telear RMS %.4f px (%zu pairs used, baseline %.4f "
      "squares), OpenCV stereo_calib reference RMS %.4f px (baseline %.4f squares)\n",
      telear->rms_px, telear->views.size(), telear->baseline(), reference.rms,
      cv::norm(reference.T));
  RecordProperty("telear_rms_px", std::to_string(telear->rms_px));
  RecordProperty("opencv_reference_rms_px", std::to_string(reference.rms));
  EXPECT_LE(telear->rms_px, reference.rms + 1e-6);
  EXPECT_EQ(telear->views.size() + telear->rejected.size(), 13u);

  // The two calibrations agree on the geometry: the baseline is about 3.33 squares.
  EXPECT_NEAR(telear->baseline(), cv::norm(reference.T), 0.03);
  EXPECT_LT(telear->baseline_std, 0.01);
  EXPECT_LT(telear->T[0], 0.0);  // the right camera is to the right (x_R = R x_L + T)
}

TEST_F(RealStereoSet, OnTheSameCornersTelearsSolverFitsAtLeastAsWell) {
  // Corner detection aside: the sample's own corners into telear's calibration, every pair
  // kept. telear's model (fx, fy per camera, full kc) contains the sample's restricted one.
  const Reference& reference = reference_on_all_pairs();
  const CalibrationPattern pattern = *parse_calibration_pattern("chessboard:9x6:1");
  StereoCalibrationOptions keep_all;
  keep_all.calibration.outlier_factor = 0.0;
  const auto telear = calibrate_stereo(pattern, reference.views, {640, 480}, keep_all);
  ASSERT_TRUE(telear.ok()) << telear.error().message;
  std::printf("same corners (cornerSubPix 11x11): telear RMS %.4f px, reference %.4f px\n",
              telear->rms_px, reference.rms);
  EXPECT_LE(telear->rms_px, reference.rms + 1e-6);
  EXPECT_EQ(telear->views.size(), 13u);
}

}  // namespace
}  // namespace telear::vision
