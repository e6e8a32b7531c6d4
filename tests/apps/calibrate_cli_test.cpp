// `telear calibrate` end to end on OpenCV's real stereo set (Debian's opencv-doc package),
// and its bad-input paths: one clear line on stderr, a non-zero exit, no output file.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "telear/vision/calibration_file.hpp"
#include "telear/vision/camera_file.hpp"
#include "telear/vision/image_file.hpp"
#include "test_util/temp_dir.hpp"

namespace telear {
namespace {

namespace fs = std::filesystem;
using test::run_telear;
using ::testing::HasSubstr;

const std::string kSamples = "/usr/share/doc/opencv-doc/examples/data";

std::vector<std::string> files_in(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename());
  std::sort(names.begin(), names.end());
  return names;
}

class CalibrateCli : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(fs::exists(kSamples + "/left01.jpg"))
        << "install Debian's opencv-doc package (scripts/install-deps.sh does): the test uses "
           "OpenCV's stereo chessboard images in "
        << kSamples;
  }
};

TEST_F(CalibrateCli, StereoSetGivesACameraFileAndAReport) {
  test_files::TempDir tmp("calibrate_cli_stereo");
  const std::string dir = tmp.string();
  const auto r =
      run_telear("calibrate --left '" + kSamples + "/left[0-9]*.jpg' --right '" + kSamples +
                 "/right[0-9]*.jpg' --pattern chessboard:9x6:1 -o " + dir +
                 "/stereo.yaml --report " + dir + "/report.json --camera-info " + dir + "/rig");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_TRUE(r.err.empty()) << r.err;
  EXPECT_THAT(r.out, HasSubstr("detecting chessboard:9x6:1 in 13 image pairs\n"));
  EXPECT_THAT(r.out, HasSubstr("[ 1/13] left01.jpg + right01.jpg: found\n"));
  EXPECT_THAT(r.out, HasSubstr("[13/13] left14.jpg + right14.jpg: found\n"));
  EXPECT_THAT(r.out, HasSubstr("13 pairs given, 13 used, 0 rejected"));
  EXPECT_THAT(r.out, HasSubstr("stereo RMS 0."));
  EXPECT_EQ(files_in(dir), (std::vector<std::string>{"report.json", "rig_left.yaml",
                                                     "rig_right.yaml", "stereo.yaml"}));

  const auto cameras = vision::load_camera_file(dir + "/stereo.yaml");
  ASSERT_TRUE(cameras.ok()) << cameras.error().message;
  ASSERT_TRUE(cameras->is_stereo());
  EXPECT_EQ(cameras->left.width, 640);
  EXPECT_NEAR(cameras->left.fx, 534.0, 5.0);
  EXPECT_FALSE(cameras->left_has_pose);  // calibrated, not registered
  const auto geometry = vision::load_stereo_geometry(dir + "/stereo.yaml");
  ASSERT_TRUE(geometry.ok()) << geometry.error().message;
  EXPECT_NEAR(cv::norm(geometry->T), 3.33, 0.05);  // squares

  std::ifstream in(dir + "/report.json");
  const auto report = nlohmann::json::parse(in);
  EXPECT_EQ(report["kind"], "stereo");
  EXPECT_EQ(report["views_used"], 13);
  EXPECT_LT(report["rms_px"].get<double>(), 0.3);
  EXPECT_EQ(report["views"].size(), 13u);

  const auto left_info = vision::load_camera_file(dir + "/rig_left.yaml");
  ASSERT_TRUE(left_info.ok()) << left_info.error().message;
  EXPECT_NEAR(left_info->left.fx, cameras->left.fx, 1e-9);
}

TEST_F(CalibrateCli, ImagesWithoutThePatternOrCorruptAreSkippedAndSaidSo) {
  test_files::TempDir tmp("calibrate_cli_skip");
  const std::string dir = tmp.string();
  const std::string images = dir + "/images";
  fs::create_directories(images);
  for (const char* name : {"left01.jpg", "left03.jpg", "left04.jpg", "left05.jpg"}) {
    fs::copy_file(kSamples + "/" + name, images + "/" + name);
  }
  ASSERT_TRUE(
      vision::write_png_file(images + "/left06.png", cv::Mat(480, 640, CV_8UC1, cv::Scalar(200))));
  std::ofstream(images + "/left07.png") << "not an image";
  const auto r =
      run_telear("calibrate --left '" + images + "/left*' --pattern chessboard:9x6:1 -o " + dir +
                 "/camera.yaml --report " + dir + "/report.json");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_THAT(r.out, HasSubstr("[5/6] left06.png: no pattern found (the whole "
                               "chessboard:9x6:1 must be visible; COLSxROWS counts inner "
                               "corners)\n"));
  EXPECT_THAT(r.out, HasSubstr("[6/6] left07.png: cannot decode image (corrupt or not an image "
                               "file); replace or delete it\n"));
  EXPECT_THAT(r.out, HasSubstr("6 images given, 4 used, 2 rejected"));
  std::ifstream in(dir + "/report.json");
  const auto report = nlohmann::json::parse(in);
  EXPECT_EQ(report["kind"], "mono");
  EXPECT_EQ(report["views"][4]["status"], "rejected");
  EXPECT_THAT(report["views"][4]["reason"].get<std::string>(), HasSubstr("no pattern found"));
  EXPECT_THAT(report["views"][5]["reason"].get<std::string>(), HasSubstr("cannot decode image"));
  EXPECT_TRUE(vision::load_camera_file(dir + "/camera.yaml").ok());
}

TEST_F(CalibrateCli, BadInputGetsOneLineThatSaysWhatToDoAndWritesNothing) {
  test_files::TempDir tmp("calibrate_cli_bad");
  const std::string dir = tmp.string();
  const std::string left = "--left '" + kSamples + "/left[0-9]*.jpg'";
  const std::string right = "--right '" + kSamples + "/right[0-9]*.jpg'";
  const std::string out = " -o " + dir + "/stereo.yaml --report " + dir + "/report.json";
  struct Case {
    std::string args;
    std::string message;
  };
  const Case cases[] = {
      {left + " " + right + " --pattern chessboard:9x6" + out,
       "telear calibrate: --pattern: pattern 'chessboard:9x6': not three fields separated by "
       "':' (expected chessboard:COLSxROWS:SQUARE_M"},
      {left + " " + right + " --pattern chessboard:9x6:1 -o " + dir + "/missing/stereo.yaml",
       "telear calibrate: -o '" + dir + "/missing/stereo.yaml': directory '" + dir +
           "/missing' does not exist; create it or choose another output path"},
      {left + " " + right + " --pattern chessboard:9x6:1 -o " + dir + "/stereo.yaml --report " +
           dir + "/nowhere/report.json",
       "telear calibrate: --report '" + dir + "/nowhere/report.json': directory '" + dir +
           "/nowhere' does not exist"},
      {left + " --right '" + kSamples + "/right0[1-4].jpg' --pattern chessboard:9x6:1" + out,
       "telear calibrate: 13 left images but 4 right images; every left image "
       "needs the right image taken at the same moment"},
      {"--left '" + kSamples + "/left0[12].jpg' --right '" + kSamples +
           "/right0[12].jpg' --pattern chessboard:9x6:1" + out,
       "telear calibrate: too few views: 2 usable stereo pairs (need at least 3); capture more "
       "images that show the whole pattern"},
      {"--left '" + kSamples + "/nothing*.png' --pattern chessboard:9x6:1" + out,
       "telear calibrate: --left '" + kSamples +
           "/nothing*.png' matches no file; check the "
           "directory and the pattern, and quote it"},
      {left + " " + right + " --pattern chessboard:8x6:1" + out,
       "telear calibrate: the pattern chessboard:8x6:1 is smaller than the board in "
       "'left01.jpg', which has 9x6 inner corners; calibrate with chessboard:9x6:1"},
      {left + " --pattern chessboard:9x6:1 --outlier-factor 0.5" + out,
       "telear calibrate: --outlier-factor: outlier_factor must be 0 (keep every view) or a "
       "finite number > 1"},
  };
  for (const Case& c : cases) {
    const auto r = run_telear("calibrate " + c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.out;
    EXPECT_THAT(r.err, HasSubstr(c.message)) << c.args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(files_in(dir).empty()) << c.args;
  }
}

}  // namespace
}  // namespace telear
