// The accuracy chain of issue 4 on the fisheye rig (data/rigs/puma560_fisheye_rig.yaml, two
// 162-degree equidistant cameras), as a user runs it: rendered calibration images -> telear
// calibrate --model equidistant -> rendered marker observations -> telear register ->
// telear eval against the simulator's truth, with every target of the pinhole rig's chain
// (tests/apps/sim_chain_cli_test.cpp): fx, fy within 0.2 %, cc within 1 px, registration
// within 1 mm and 0.1 deg, the overlay on the arm <= 0.5 px RMS. Seeds are fixed (about two
// minutes on 2 cores, headless EGL). Also `--model`'s bad input.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "eval_report.hpp"
#include "test_util/temp_dir.hpp"

namespace telear {
namespace {

using test::run_telear;
using ::testing::HasSubstr;

TEST(SimAccuracyChainFisheye, RenderedImagesToRegisteredGhostMeetEveryTarget) {
  test_files::TempDir tmp("sim_chain_fisheye");
  const std::string d = tmp.string();
  const std::string rig = std::string(TELEAR_TEST_DATA_DIR) + "/rigs/puma560_fisheye_rig.yaml";

  auto step = [](const std::string& args) {
    const auto r = run_telear(args);
    EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.err;
    return r;
  };
  ASSERT_EQ(step("sim capture --rig " + rig + " --views 20 --seed 1 -o " + d + "/cap").exit_code,
            0);
  const auto calibrated =
      step("calibrate --model equidistant --left '" + d + "/cap/left*.png' --right '" + d +
           "/cap/right*.png' --pattern chessboard:9x6:0.03 -o " + d + "/stereo.yaml --report " + d +
           "/report.json");
  ASSERT_EQ(calibrated.exit_code, 0);
  EXPECT_THAT(calibrated.out, HasSubstr("lens model equidistant: D = (k1, k2, k3, k4)"));
  ASSERT_EQ(step("sim observations --rig " + rig + " --robot puma560 --configs 20 --seed 1 -o " +
                 d + "/obs.yaml")
                .exit_code,
            0);
  ASSERT_EQ(step("register --rig " + d + "/stereo.yaml --robot puma560 --observations " + d +
                 "/obs.yaml -o " + d + "/registered.yaml")
                .exit_code,
            0);
  ASSERT_EQ(step("eval --truth " + d + "/cap/truth.yaml --estimate " + d +
                 "/registered.yaml --robot puma560 --json " + d + "/eval.json")
                .exit_code,
            0);

  std::ifstream calibration_in(d + "/report.json");
  const nlohmann::json calibration = nlohmann::json::parse(calibration_in);
  for (const char* eye : {"left", "right"}) {
    const nlohmann::json& camera = calibration["cameras"][eye];
    EXPECT_EQ(camera["distortion_model"], "equidistant");
    EXPECT_TRUE(camera.contains("k4"));
    EXPECT_FALSE(camera.contains("p1"));
    EXPECT_GT(camera["k1"]["std"].get<double>(), 0.0);
  }

  const nlohmann::json report = test::expect_eval_report_passes(d + "/eval.json");
  ASSERT_FALSE(report.empty());
  for (const char* eye : {"left", "right"}) {
    const double rms = report[eye]["overlay_rms_px"].get<double>();
    std::printf("%s: overlay RMS %.3f px, max %.3f px, registration %.3f mm %.4f deg\n", eye, rms,
                report[eye]["overlay_max_px"].get<double>(),
                report[eye]["registration_mm"].get<double>(),
                report[eye]["registration_deg"].get<double>());
    EXPECT_LE(rms, 0.5) << eye;
    EXPECT_LT(report[eye]["registration_mm"].get<double>(), 1.0) << eye;
  }
  EXPECT_NEAR(report["baseline_estimate_mm"].get<double>(), 60.0, 0.5);
}

TEST(CalibrateModel, BadModelOptionsAreOneLineErrors) {
  test_files::TempDir tmp("calibrate_model");
  const std::string never = tmp.file("never.yaml");
  const std::string common =
      "calibrate --left 'nothing*.png' --pattern chessboard:9x6:0.03 -o " + never;
  auto unknown = run_telear(common + " --model pinhole");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_EQ(unknown.err,
            "telear calibrate: --model: unknown distortion model 'pinhole' (expected plumb_bob, "
            "rational_polynomial or equidistant)\n");
  auto tangential = run_telear(common + " --model equidistant --zero-tangential");
  EXPECT_EQ(tangential.exit_code, 2);
  EXPECT_THAT(tangential.err, HasSubstr("--zero-tangential: the equidistant (fisheye) model has "
                                        "no tangential terms"));
  auto k3 = run_telear(common + " --model rational_polynomial --estimate-k3");
  EXPECT_EQ(k3.exit_code, 2);
  EXPECT_THAT(k3.err, HasSubstr("--estimate-k3: applies to plumb_bob only"));
  EXPECT_FALSE(std::filesystem::exists(never));
}

}  // namespace
}  // namespace telear
