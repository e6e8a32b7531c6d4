// `telear register` and `telear eval` end to end: synthetic marker observations of the
// shipped stereo rig (the truth: data/cameras/puma560_stereo.yaml, 0.1 px noise, fixed seed)
// are written with the observations writer, registered from a calibrated-but-unregistered
// camera file, and evaluated against the truth. Plus bad input: one line on stderr, exit 2,
// no output file.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "cli_runner.hpp"
#include "synthetic_observations.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/vision/calibration_file.hpp"
#include "telear/vision/camera_file.hpp"
#include "telear/vision/observations_file.hpp"
#include "telear/vision/registration.hpp"
#include "test_util/temp_dir.hpp"
#include "test_util/test_util.hpp"

namespace telear {
namespace {

namespace fs = std::filesystem;
using test::run_telear;
using ::testing::HasSubstr;

void write(const std::string& path, const std::string& text) {
  std::ofstream file(path);
  file << text;
}

std::string truth_path() {
  return test::data_path("cameras/puma560_stereo.yaml");
}

// A flange marker at `count` random configurations where both eyes see it, projected by the
// true cameras plus N(0, 0.1 px).
vision::RegistrationObservations synthetic_observations(int count, unsigned seed) {
  return test::synthetic_observations(*test::puma560(), test::shipped_stereo_cameras(),
                                      test::flange_marker_corners(), count, 0.1, seed);
}

// What a stereo `telear calibrate` hands over: the true intrinsics, no registration (identity
// poses here), and the pair's geometry R, T.
std::string calibrated_rig_yaml() {
  vision::StereoCameraModel rig = test::shipped_stereo_cameras();
  const Eigen::Isometry3d T_right_left =
      vision::right_from_left(rig.left.T_cam_base, rig.right.T_cam_base);
  rig.left.T_cam_base = Eigen::Isometry3d::Identity();
  rig.right.T_cam_base = Eigen::Isometry3d::Identity();
  std::ostringstream s;
  s << std::setprecision(17) << vision::opencv_stereo_camera_yaml(rig);
  s << "R: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n   data: [ ";
  for (int i = 0; i < 9; ++i) s << T_right_left.linear()(i / 3, i % 3) << (i < 8 ? ", " : " ]\n");
  s << "T: !!opencv-matrix\n   rows: 3\n   cols: 1\n   dt: d\n   data: [ ";
  for (int i = 0; i < 3; ++i) s << T_right_left.translation()(i) << (i < 2 ? ", " : " ]\n");
  return s.str();
}

// The value of a row of eval's target table, e.g. "left registration mm".
double table_value(const std::string& out, const std::string& name) {
  const std::size_t at = out.find("  " + name + " ");
  EXPECT_NE(at, std::string::npos) << name << " not in:\n" << out;
  if (at == std::string::npos) return -1.0;
  return std::stod(out.substr(at + 2 + name.size()));
}

TEST(RegisterEvalCli, RegistersSyntheticObservationsAndEvalPassesTheTargets) {
  test_files::TempDir tmp("register_cli_end_to_end");
  const std::string dir = tmp.string();
  ASSERT_TRUE(
      vision::write_observations_file(synthetic_observations(15, 7), dir + "/obs.yaml").ok());
  write(dir + "/stereo.yaml", calibrated_rig_yaml());

  const auto r = run_telear("register --rig " + dir + "/stereo.yaml --robot puma560 " +
                            "--observations " + dir + "/obs.yaml -o " + dir + "/registered.yaml");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_TRUE(r.err.empty()) << r.err;
  EXPECT_THAT(r.out, HasSubstr("from 15 configurations (15 distinct) of 4 point(s) each"));
  EXPECT_THAT(r.out, HasSubstr("residuals after the PnP start:"));
  EXPECT_THAT(r.out, HasSubstr("residuals after refinement ("));
  EXPECT_THAT(r.out, HasSubstr("left                       60 points"));

  Result<vision::CameraFile> registered = vision::load_camera_file(dir + "/registered.yaml");
  ASSERT_TRUE(registered.ok()) << registered.error().message;
  ASSERT_TRUE(registered->is_stereo());
  EXPECT_TRUE(registered->left_has_pose);
  EXPECT_TRUE(registered->right_has_pose);
  // The geometry is kept, so the output can be registered again.
  EXPECT_TRUE(vision::load_stereo_geometry(dir + "/registered.yaml").ok());

  const auto e = run_telear("eval --truth " + truth_path() + " --estimate " + dir +
                            "/registered.yaml --robot puma560 --configurations 4 --json " + dir +
                            "/report.json");
  ASSERT_EQ(e.exit_code, 0) << e.err << e.out;
  for (const char* eye : {"left", "right"}) {
    const std::string p = std::string(eye) + " ";
    EXPECT_LT(table_value(e.out, p + "registration mm"), 1.0) << e.out;
    EXPECT_LT(table_value(e.out, p + "registration deg"), 0.1) << e.out;
    EXPECT_LT(table_value(e.out, p + "overlay RMS px"), 0.5) << e.out;
    EXPECT_LT(table_value(e.out, p + "overlay max px"), 1.5) << e.out;
    EXPECT_EQ(table_value(e.out, p + "fx error %"), 0.0);  // the true intrinsics
  }
  EXPECT_THAT(e.out, HasSubstr("overall: PASS"));
  std::ifstream json_file(dir + "/report.json");
  const nlohmann::json report = nlohmann::json::parse(json_file);
  EXPECT_TRUE(report["pass"].get<bool>());
  EXPECT_LT(report["left"]["registration_mm"].get<double>(), 1.0);
  EXPECT_NEAR(report["baseline_truth_mm"].get<double>(), 60.0, 1.0);
}

TEST(RegisterEvalCli, ARegisteredFileWithoutRAndTUsesItsPoses) {
  // The truth file has both T_cam_base and no R, T: the geometry comes from the poses.
  test_files::TempDir tmp("register_cli_poses");
  const std::string dir = tmp.string();
  ASSERT_TRUE(
      vision::write_observations_file(synthetic_observations(6, 3), dir + "/obs.yaml").ok());
  const auto r = run_telear("register --rig " + truth_path() + " --observations " + dir +
                            "/obs.yaml -o " + dir + "/out.yaml");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_TRUE(fs::exists(dir + "/out.yaml"));
}

TEST(RegisterEvalCli, BadInputIsOneLineAndNoOutputFile) {
  test_files::TempDir tmp("register_cli_bad");
  const std::string dir = tmp.string();
  write(dir + "/stereo.yaml", calibrated_rig_yaml());
  vision::RegistrationObservations two = synthetic_observations(2, 5);
  ASSERT_TRUE(vision::write_observations_file(two, dir + "/two.yaml").ok());
  const std::string out = dir + "/out.yaml";

  auto r = run_telear("register --rig " + dir + "/stereo.yaml --observations " + dir +
                      "/missing.yaml -o " + out);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("telear register: --observations: "));
  EXPECT_THAT(r.err, HasSubstr("missing.yaml"));

  r = run_telear("register --rig " + dir + "/stereo.yaml --observations " + dir + "/two.yaml -o " +
                 out);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("telear register: observations '"));
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;

  write(dir + "/mono.yaml", vision::opencv_camera_yaml(test::shipped_stereo_cameras().left));
  r = run_telear("register --rig " + dir + "/mono.yaml --observations " + dir + "/two.yaml -o " +
                 out);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("is a mono camera file; registration needs a stereo pair"));

  r = run_telear("register --rig " + dir + "/stereo.yaml --observations " + dir + "/two.yaml -o " +
                 dir + "/no/such/dir/out.yaml");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("telear register: -o"));
  EXPECT_FALSE(fs::exists(out));

  r = run_telear("eval --truth " + truth_path() + " --estimate " + dir + "/mono.yaml");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("telear eval: --estimate '"));
  EXPECT_THAT(r.err, HasSubstr("is a mono camera file"));

  write(dir + "/broken.yaml", "left: [1, 2\n");
  r = run_telear("eval --truth " + dir + "/broken.yaml --estimate " + truth_path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("telear eval: --truth: camera file '"));
}

}  // namespace
}  // namespace telear
