// The accuracy chain of issue 4, end to end on the simulated rig, as a user runs it:
// rendered calibration images -> telear calibrate -> rendered marker observations ->
// telear register -> telear eval against the simulator's truth. Every target must pass:
// fx, fy within 0.2 %, cc within 1 px, baseline within 0.5 mm, registration within 1 mm and
// 0.1 deg, overlay error <= 0.5 px RMS and <= 1.5 px max per eye. Seeds are fixed, so the
// run is deterministic (about 20 s on 2 cores, headless EGL).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "eval_report.hpp"
#include "test_util/temp_dir.hpp"

namespace telear {
namespace {

using test::run_telear;

TEST(SimAccuracyChain, RenderedImagesToRegisteredGhostMeetEveryTarget) {
  test_files::TempDir tmp("sim_chain");
  const std::string d = tmp.string();
  const std::string rig = std::string(TELEAR_TEST_DATA_DIR) + "/rigs/puma560_rig.yaml";

  auto step = [](const std::string& args) {
    const auto r = run_telear(args);
    EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.err;
    return r.exit_code == 0;
  };
  ASSERT_TRUE(step("sim capture --rig " + rig + " --views 20 --seed 1 -o " + d + "/cap"));
  ASSERT_TRUE(step("calibrate --left '" + d + "/cap/left*.png' --right '" + d +
                   "/cap/right*.png' --pattern chessboard:9x6:0.03 -o " + d + "/stereo.yaml"));
  ASSERT_TRUE(step("sim observations --rig " + rig + " --robot puma560 --configs 20 --seed 1 -o " +
                   d + "/obs.yaml"));
  ASSERT_TRUE(step("register --rig " + d + "/stereo.yaml --robot puma560 --observations " + d +
                   "/obs.yaml -o " + d + "/registered.yaml"));
  ASSERT_TRUE(step("eval --truth " + d + "/cap/truth.yaml --estimate " + d +
                   "/registered.yaml --robot puma560 --json " + d + "/eval.json"));

  const nlohmann::json report = test::expect_eval_report_passes(d + "/eval.json");
  ASSERT_FALSE(report.empty());
  for (const char* eye : {"left", "right"}) {
    EXPECT_LT(report[eye]["overlay_rms_px"].get<double>(), 0.5) << eye;
    EXPECT_LT(report[eye]["registration_mm"].get<double>(), 1.0) << eye;
  }
  EXPECT_NEAR(report["baseline_estimate_mm"].get<double>(), 60.0, 0.5);
}

}  // namespace
}  // namespace telear
