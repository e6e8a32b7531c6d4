// From files to views (globs, decoding, detection, pairing, what is skipped and why) and from
// a calibration to files (camera YAML with the stereo extras, ROS camera_info, the JSON
// report), all-or-nothing writes included.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "rendered_pattern.hpp"
#include "synthetic_observations.hpp"
#include "synthetic_views.hpp"
#include "telear/vision/calibration_file.hpp"
#include "telear/vision/calibration_images.hpp"
#include "telear/vision/calibration_report.hpp"
#include "telear/vision/camera_file.hpp"
#include "telear/vision/image_file.hpp"
#include "test_util/temp_dir.hpp"

namespace telear::vision {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

using test::chessboard_9x6;

void write_board(const std::string& path, double width, double tilt, double roll,
                 cv::Size size = {640, 480}) {
  const cv::Matx33d H = test::view_homography(chessboard_9x6(), size, width, tilt, roll);
  ASSERT_TRUE(write_png_file(path, test::render_pattern(chessboard_9x6(), H, size)));
}

std::vector<std::string> files_in(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(CalibrationImages, GlobIsSortedAndAnEmptyMatchSaysWhatToDo) {
  test_files::TempDir tmp("calib_glob");
  const std::string dir = tmp.string();
  for (const char* name : {"b.png", "a.png", "c.txt"}) std::ofstream(dir + "/" + name) << "x";
  const auto paths = expand_image_glob(dir + "/*.png", "--left");
  ASSERT_TRUE(paths.ok()) << paths.error().message;
  EXPECT_EQ(*paths, (std::vector<std::string>{dir + "/a.png", dir + "/b.png"}));
  const auto none = expand_image_glob(dir + "/left*.png", "--left");
  ASSERT_FALSE(none.ok());
  EXPECT_EQ(none.error().message,
            "--left '" + dir +
                "/left*.png' matches no file; check the directory and the pattern, and quote it "
                "so that telear expands it (e.g. 'images/left*.png')");
}

TEST(CalibrationImages, SkipsImagesWithoutThePatternCorruptOrOfAnotherSizeAndSaysWhy) {
  test_files::TempDir tmp("calib_mono");
  const std::string dir = tmp.string();
  write_board(dir + "/01.png", 380.0, 25.0, 5.0);
  ASSERT_TRUE(write_png_file(dir + "/02.png", cv::Mat(480, 640, CV_8UC1, cv::Scalar(128))));
  std::ofstream(dir + "/03.png") << "\x89PNG\r\n\x1a\n this is not a PNG file";  // corrupt
  write_board(dir + "/04.png", 300.0, -30.0, -8.0, {800, 600});                  // other size
  write_board(dir + "/05.png", 300.0, 40.0, 12.0);

  std::vector<DetectionProgress> progress;
  const auto result =
      detect_in_images(*expand_image_glob(dir + "/*.png", "--left"), chessboard_9x6(),
                       [&progress](const DetectionProgress& p) { progress.push_back(p); });
  ASSERT_TRUE(result.ok()) << result.error().message;
  EXPECT_EQ(result->image_size, cv::Size(640, 480));
  ASSERT_EQ(result->views.size(), 2u);
  EXPECT_EQ(result->views[0].name, dir + "/01.png");
  EXPECT_EQ(result->views[1].name, dir + "/05.png");
  EXPECT_EQ(result->views[0].image_points.size(), 54u);
  ASSERT_EQ(result->rejected.size(), 3u);
  EXPECT_EQ(result->rejected[0].name, dir + "/02.png");
  EXPECT_EQ(result->rejected[0].reason,
            "no pattern found (the whole chessboard:9x6:0.03 must be visible; COLSxROWS counts "
            "inner corners)");
  EXPECT_EQ(result->rejected[1].reason,
            "cannot decode image (corrupt or not an image file); replace or delete it");
  EXPECT_EQ(result->rejected[2].reason,
            "image is 800x600 but the first image is 640x480; use images from one camera at "
            "one resolution");

  ASSERT_EQ(progress.size(), 5u);
  EXPECT_EQ(progress[0].index, 1u);
  EXPECT_EQ(progress[0].count, 5u);
  EXPECT_EQ(progress[0].name, "01.png");
  EXPECT_TRUE(progress[0].found);
  EXPECT_EQ(progress[0].outcome, "found");
  EXPECT_FALSE(progress[1].found);
  EXPECT_THAT(progress[1].outcome, HasSubstr("no pattern found"));

  // Nothing decodable at all is an error, not an empty calibration.
  const auto nothing = detect_in_images({dir + "/03.png"}, chessboard_9x6());
  ASSERT_FALSE(nothing.ok());
  EXPECT_THAT(nothing.error().message, HasSubstr("none of the 1 images could be decoded"));
}

TEST(CalibrationImages, PairsNeedEqualCountsAndBothImages) {
  test_files::TempDir tmp("calib_pairs");
  const std::string dir = tmp.string();
  write_board(dir + "/left1.png", 380.0, 25.0, 5.0);
  write_board(dir + "/right1.png", 370.0, 28.0, 5.0);
  write_board(dir + "/left2.png", 300.0, -30.0, -8.0);
  ASSERT_TRUE(write_png_file(dir + "/right2.png", cv::Mat(480, 640, CV_8UC1, cv::Scalar(128))));
  write_board(dir + "/left3.png", 300.0, 40.0, 12.0);

  const auto left = *expand_image_glob(dir + "/left*.png", "--left");
  const auto right = *expand_image_glob(dir + "/right*.png", "--right");
  const auto unequal = detect_in_image_pairs(left, right, chessboard_9x6());
  ASSERT_FALSE(unequal.ok());
  EXPECT_EQ(unequal.error().message,
            "3 left images but 2 right images; every left image needs the right "
            "image taken at the same moment (pairs are matched in sorted name order): remove "
            "the unpaired images");

  std::vector<std::string> progress;
  const auto pairs = detect_in_image_pairs(
      {left[0], left[1]}, right, chessboard_9x6(),
      [&progress](const DetectionProgress& p) { progress.push_back(p.name + ": " + p.outcome); });
  ASSERT_TRUE(pairs.ok()) << pairs.error().message;
  ASSERT_EQ(pairs->views.size(), 1u);
  EXPECT_EQ(pairs->views[0].left_name, left[0]);
  EXPECT_EQ(pairs->views[0].right_name, right[0]);
  ASSERT_EQ(pairs->rejected.size(), 1u);
  EXPECT_EQ(pairs->rejected[0].name, left[1]);
  EXPECT_EQ(pairs->rejected[0].right_name, right[1]);
  EXPECT_EQ(pairs->rejected[0].reason,
            "right: no pattern found (the whole chessboard:9x6:0.03 must be visible; "
            "COLSxROWS counts inner corners)");
  EXPECT_EQ(progress,
            (std::vector<std::string>{"left1.png + right1.png: found",
                                      "left2.png + right2.png: right: no pattern found (the whole "
                                      "chessboard:9x6:0.03 must be visible; COLSxROWS counts inner "
                                      "corners)"}));
}

// [SECTION] output files

StereoCalibration synthetic_calibration() {
  std::mt19937_64 rng(42);
  const test::SyntheticRig rig = test::default_rig();
  const auto poses = test::random_pattern_poses(rig, chessboard_9x6(), 8, rng);
  auto result = calibrate_stereo(
      chessboard_9x6(), test::stereo_views(rig, chessboard_9x6(), poses, 0.1, rng), {640, 480});
  EXPECT_TRUE(result.ok());
  return *result;
}

TEST(CalibrationFile, StereoYamlReadsBackAsCamerasAndCarriesTheStereoExtras) {
  const StereoCalibration c = synthetic_calibration();
  test_files::TempDir tmp("calib_yaml");
  const std::string dir = tmp.string();
  const std::string path = dir + "/stereo.yaml";
  ASSERT_TRUE(write_files_atomically({{path, stereo_calibration_yaml(c, chessboard_9x6())}}).ok());
  EXPECT_EQ(files_in(dir), std::vector<std::string>{"stereo.yaml"});  // no temporaries left

  const auto file = load_camera_file(path);
  ASSERT_TRUE(file.ok()) << file.error().message;
  ASSERT_TRUE(file->is_stereo());
  EXPECT_NEAR(file->left.fx, c.cameras.left.fx, 1e-9);
  EXPECT_NEAR(file->right->kc.k1, c.cameras.right.kc.k1, 1e-12);
  // Calibrated, not registered: no T_cam_base until `telear register` adds it.
  EXPECT_FALSE(file->left_has_pose);
  EXPECT_FALSE(file->right_has_pose);
  const auto geometry = load_stereo_geometry(path);
  ASSERT_TRUE(geometry.ok()) << geometry.error().message;
  EXPECT_LT(cv::norm(geometry->R - c.R), 1e-12);
  EXPECT_LT(cv::norm(geometry->T - c.T), 1e-12);

  cv::FileStorage fs(path, cv::FileStorage::READ);
  ASSERT_TRUE(fs.isOpened());
  cv::Mat R, T, P2, Q;
  fs["R"] >> R;
  fs["T"] >> T;
  fs["P2"] >> P2;
  fs["Q"] >> Q;
  ASSERT_EQ(R.size(), cv::Size(3, 3));
  ASSERT_EQ(T.total(), 3u);
  ASSERT_EQ(P2.size(), cv::Size(4, 3));
  ASSERT_EQ(Q.size(), cv::Size(4, 4));
  EXPECT_NEAR(cv::norm(T), c.baseline(), 1e-12);
  EXPECT_EQ(static_cast<std::string>(fs["calibration_pattern"]), "chessboard:9x6:0.03");
  EXPECT_NEAR(static_cast<double>(fs["rms_px"]), c.rms_px, 1e-12);
  cv::Mat K;
  fs["left"]["camera_matrix"] >> K;
  EXPECT_NEAR(K.at<double>(0, 2), c.cameras.left.cx, 1e-9);
}

TEST(CalibrationFile, StereoGeometryErrorsNameTheFileAndTheProblem) {
  test_files::TempDir tmp("calib_geometry");
  const std::string dir = tmp.string();
  std::ofstream(dir + "/mono.yaml") << "%YAML:1.0\n---\nimage_width: 640\n";
  EXPECT_EQ(load_stereo_geometry(dir + "/mono.yaml").error().message,
            "stereo calibration '" + dir +
                "/mono.yaml': no R and T (it is not the output of a stereo `telear calibrate`)");
  std::ofstream(dir + "/bad.yaml")
      << "%YAML:1.0\n---\nR: !!opencv-matrix\n  rows: 3\n  cols: 3\n  dt: d\n  data: [1, 0, "
         "0, 0, 1, 0, 0, 0, 2]\nT: !!opencv-matrix\n  rows: 3\n  cols: 1\n  dt: d\n  data: [1, "
         "0, 0]\n";
  EXPECT_THAT(load_stereo_geometry(dir + "/bad.yaml").error().message,
              HasSubstr("R is not a rotation"));
  EXPECT_EQ(load_stereo_geometry(dir + "/none.yaml").error().message,
            "stereo calibration '" + dir + "/none.yaml': no such file");
}

TEST(CalibrationFile, RosCameraInfoCarriesTheRectification) {
  const StereoCalibration c = synthetic_calibration();
  test_files::TempDir tmp("calib_ros");
  const std::string dir = tmp.string();
  const std::string path = dir + "/right.yaml";
  ASSERT_TRUE(write_files_atomically({{path, ros_stereo_camera_info_yaml(c, true, "right")}}).ok());
  const auto file = load_camera_file(path);  // telear reads ROS camera_info too
  ASSERT_TRUE(file.ok()) << file.error().message;
  EXPECT_NEAR(file->left.fy, c.cameras.right.fy, 1e-9);
  EXPECT_NEAR(file->left.kc.p2, c.cameras.right.kc.p2, 1e-15);
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_THAT(text, HasSubstr("camera_name: right\n"));
  EXPECT_THAT(text, HasSubstr("distortion_model: plumb_bob\n"));
  EXPECT_THAT(text, HasSubstr("projection_matrix:\n  rows: 3\n  cols: 4\n"));
}

// calibrate_stereo() -> ros_stereo_camera_info_yaml() left and right -> the pair read back
// keeps the calibration's R and T (from R1, R2 and P2's Tx), for each lens model; the
// FileStorage file written as XML carries the same.
TEST(CalibrationFile, RosStereoPairAndXmlKeepTheGeometryOfEveryModel) {
  const std::vector<std::pair<DistortionModel, std::vector<double>>> lenses = {
      {DistortionModel::plumb_bob, {-0.3, 0.1, 0.001, -0.0005, 0.0}},
      {DistortionModel::rational_polynomial, {-0.28, 0.09, 0.001, -0.0005, 0.0, 0.05, 0.0, 0.0}},
      {DistortionModel::equidistant, {-0.02, 0.004, 0.0, 0.0}}};
  for (const auto& [model, d] : lenses) {
    SCOPED_TRACE(distortion_model_name(model));
    test::SyntheticRig rig = test::default_rig();
    rig.left.kc = rig.right.kc = *Distortion::from_coefficients(model, d);
    // Seed 3, 12 views: with seed 42's 10 views cv::fisheye::stereoCalibrate's initialisation
    // stops on an assertion (abs_max < threshold), which is not what this test is about.
    std::mt19937_64 rng(3);
    const auto poses = test::random_pattern_poses(rig, chessboard_9x6(), 12, rng);
    StereoCalibrationOptions options;
    options.calibration.model = model;
    auto c = calibrate_stereo(chessboard_9x6(),
                              test::stereo_views(rig, chessboard_9x6(), poses, 0.1, rng),
                              {640, 480}, options);
    ASSERT_TRUE(c.ok()) << c.error().message;
    ASSERT_EQ(c->cameras.left.kc.model, model);

    test_files::TempDir tmp(std::string("calib_pair_") + distortion_model_name(model));
    const std::string dir = tmp.string();
    const std::string left = dir + "/left.yaml", right = dir + "/right.yaml";
    const std::string xml = dir + "/stereo.xml";
    ASSERT_TRUE(write_files_atomically({{left, ros_stereo_camera_info_yaml(*c, false, "left")},
                                        {right, ros_stereo_camera_info_yaml(*c, true, "right")},
                                        {xml, stereo_calibration_yaml(*c, chessboard_9x6())}})
                    .ok());
    const auto pair = load_camera_file(left + "," + right);
    ASSERT_TRUE(pair.ok()) << pair.error().message;
    ASSERT_TRUE(pair->T_right_left.has_value());
    const auto geometry = load_stereo_geometry(left + "," + right);
    ASSERT_TRUE(geometry.ok()) << geometry.error().message;
    EXPECT_LT(cv::norm(geometry->R - c->R), 1e-12);
    EXPECT_LT(cv::norm(geometry->T - c->T), 1e-9);
    EXPECT_NEAR(cv::norm(geometry->T), c->baseline(), 1e-9);
    EXPECT_EQ(pair->right->kc.coefficients(), c->cameras.right.kc.coefficients());
    EXPECT_NEAR(pair->left.fx, c->cameras.left.fx, 1e-9);

    const auto from_xml = load_camera_file(xml);
    ASSERT_TRUE(from_xml.ok()) << from_xml.error().message;
    EXPECT_EQ(from_xml->left.kc.model, model);
    EXPECT_EQ(from_xml->right->kc.coefficients(), c->cameras.right.kc.coefficients());
    const auto xml_geometry = load_stereo_geometry(xml);
    ASSERT_TRUE(xml_geometry.ok()) << xml_geometry.error().message;
    EXPECT_EQ(xml_geometry->T, c->T);
  }
}

TEST(CalibrationFile, UnwritablePathsFailEarlyAndLeaveNothingBehind) {
  test_files::TempDir tmp("calib_unwritable");
  const std::string dir = tmp.string();
  EXPECT_TRUE(check_output_path(dir + "/stereo.yaml", "-o").ok());
  EXPECT_EQ(check_output_path(dir + "/missing/stereo.yaml", "-o").error().message,
            "-o '" + dir + "/missing/stereo.yaml': directory '" + dir +
                "/missing' does not exist; create it or choose another output path");
  EXPECT_EQ(check_output_path(dir, "-o").error().message,
            "-o '" + dir + "' is a directory; give a file name, e.g. '" + dir + "/stereo.yaml'");
  EXPECT_THAT(check_output_path("", "--report").error().message, HasSubstr("--report: empty"));

  // All or nothing: the second file cannot be written, so the first does not appear either.
  const Status s = write_files_atomically(
      {{dir + "/stereo.yaml", "a: 1\n"}, {dir + "/missing/report.json", "{}\n"}});
  ASSERT_FALSE(s.ok());
  EXPECT_THAT(s.error().message, HasSubstr("cannot write '" + dir + "/missing/report.json': "));
  EXPECT_TRUE(files_in(dir).empty());

  // An existing file is replaced only when the new one is complete.
  std::ofstream(dir + "/stereo.yaml") << "old\n";
  ASSERT_FALSE(write_files_atomically({{dir + "/stereo.yaml", "new\n"}, {dir + "/x/y", "z"}}).ok());
  std::ifstream in(dir + "/stereo.yaml");
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "old");
  EXPECT_EQ(files_in(dir), std::vector<std::string>{"stereo.yaml"});
}

TEST(CalibrationReport, JsonHasEveryParameterWithItsStandardDeviationAndEveryView) {
  CalibrationReport report;
  report.pattern = chessboard_9x6();
  report.image_size = {640, 480};
  report.stereo = synthetic_calibration();
  report.views_given = 9;
  report.skipped.push_back(
      {.name = "zz/left9.png", .right_name = "zz/right9.png", .reason = "left: no pattern found"});
  const auto j = nlohmann::json::parse(calibration_report_json(report));
  EXPECT_EQ(j["kind"], "stereo");
  EXPECT_EQ(j["pattern"], "chessboard:9x6:0.03");
  EXPECT_EQ(j["image_size"]["width"], 640);
  EXPECT_EQ(j["views_given"], 9);
  EXPECT_EQ(j["views_used"], 8);
  EXPECT_EQ(j["views_rejected"], 1);
  EXPECT_NEAR(j["rms_px"].get<double>(), report.stereo->rms_px, 1e-12);
  for (const char* camera : {"left", "right"}) {
    for (const char* p : {"fx", "fy", "cx", "cy", "alpha_c", "k1", "k2", "p1", "p2", "k3"}) {
      ASSERT_TRUE(j["cameras"][camera].contains(p)) << camera << " " << p;
      EXPECT_TRUE(j["cameras"][camera][p].contains("std")) << camera << " " << p;
    }
    EXPECT_GT(j["cameras"][camera]["fx"]["std"].get<double>(), 0.0);
    EXPECT_GT(j["cameras"][camera]["mono_rms_px"].get<double>(), 0.0);
  }
  EXPECT_NEAR(j["stereo"]["baseline"]["value"].get<double>(), report.stereo->baseline(), 1e-12);
  EXPECT_GT(j["stereo"]["baseline"]["std"].get<double>(), 0.0);
  EXPECT_EQ(j["stereo"]["T"]["std"].size(), 3u);
  EXPECT_EQ(j["stereo"]["rectification"]["P2"].size(), 3u);
  ASSERT_EQ(j["views"].size(), 9u);
  EXPECT_EQ(j["views"][0]["status"], "used");
  EXPECT_GT(j["views"][0]["rms_px"]["right"].get<double>(), 0.0);
  EXPECT_EQ(j["views"][8]["status"], "rejected");
  EXPECT_EQ(j["views"][8]["reason"], "left: no pattern found");

  const std::string summary = calibration_summary(report);
  EXPECT_THAT(summary, HasSubstr("9 pairs given, 8 used, 1 rejected"));
  EXPECT_THAT(summary, HasSubstr("  fx [px]"));
  EXPECT_THAT(summary, HasSubstr("stereo RMS "));
  EXPECT_THAT(summary, HasSubstr("left9.png + right9.png"));
  EXPECT_THAT(summary, HasSubstr("rejected: left: no pattern found"));
}

TEST(CalibrationReport, MonoReportListsPosesAndOutliers) {
  std::mt19937_64 rng(7);
  const test::SyntheticRig rig = test::default_rig();
  const auto poses = test::random_pattern_poses(rig, chessboard_9x6(), 6, rng);
  std::vector<PatternView> views;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    views.push_back({"img" + std::to_string(i) + ".png",
                     test::project_pattern(rig.left, poses[i], chessboard_9x6(), 0.1, rng)});
  }
  for (cv::Point2f& p : views[2].image_points) p.y += 1.5f * std::sin(p.x / 60.0f);
  CalibrationReport report;
  report.pattern = chessboard_9x6();
  report.image_size = {640, 480};
  report.views_given = 6;
  auto mono = calibrate_mono(chessboard_9x6(), views, {640, 480});
  ASSERT_TRUE(mono.ok()) << mono.error().message;
  report.mono = *mono;
  const auto j = nlohmann::json::parse(calibration_report_json(report));
  EXPECT_EQ(j["kind"], "mono");
  EXPECT_TRUE(j["cameras"]["camera"]["k2"].contains("value"));
  ASSERT_EQ(j["views"].size(), 6u);
  EXPECT_EQ(j["views"][2]["image"], "img2.png");
  EXPECT_EQ(j["views"][2]["status"], "rejected");
  EXPECT_THAT(j["views"][2]["reason"].get<std::string>(), HasSubstr("outlier"));
  EXPECT_EQ(j["views"][0]["translation"]["std"].size(), 3u);
  EXPECT_THAT(calibration_summary(report), HasSubstr("6 images given, 5 used, 1 rejected"));
}

}  // namespace
}  // namespace telear::vision
