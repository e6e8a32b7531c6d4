// The calibrate -> register -> evaluate pipeline (include/telear/session/
// calibration_pipeline.hpp) at a small scale (8 views, 8 marker configurations, 2x
// supersampling of the simulated rig): it runs every step and evaluates the result, a second
// run with the same key is served from the cache with the same evaluation, and a bad rig path
// is an error naming the step and the file.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "telear/lab/calibration_pipeline.hpp"
#include "test_util/temp_dir.hpp"
#include "test_util/test_util.hpp"

namespace telear::lab {
namespace {

namespace fs = std::filesystem;

CalibrationPipelineOptions small_pipeline(const std::string& cache) {
  CalibrationPipelineOptions options;
  options.rig_file = test::data_path("rigs/puma560_rig.yaml");
  options.cache_dir = cache;
  options.views = 8;
  options.configurations = 8;
  options.supersample = 2;
  return options;
}

TEST(CalibrationPipeline, CalibratesRegistersEvaluatesAndCachesTheResult) {
  test_files::TempDir tmp("pipeline");
  const fs::path cache = tmp.file("cache");
  const CalibrationPipelineOptions options = small_pipeline(cache.string());

  auto first = run_calibration_pipeline(options);
  ASSERT_TRUE(first.ok()) << first.error().message;
  EXPECT_FALSE(first->cached);
  EXPECT_TRUE(fs::exists(first->registered_file));
  for (const char* file : {"capture/truth.yaml", "capture/left_07.png", "stereo.yaml",
                           "observations.yaml", "eval.json", "key.txt"}) {
    EXPECT_TRUE(fs::exists(cache / file)) << file;
  }
  // Calibrated from 8 rendered views: close to the truth, though not to every target.
  const CalibrationEvaluation& e = first->evaluation;
  for (const EyeEvaluation* eye : {&e.left, &e.right}) {
    EXPECT_LT(std::abs(eye->fx_error_percent), 2.0);
    EXPECT_LT(eye->registration_mm, 20.0);
    EXPECT_LT(eye->overlay_rms_px, 5.0);
  }
  EXPECT_NEAR(e.baseline_truth_mm, 60.0, 1e-9);
  const nlohmann::json json = nlohmann::json::parse(e.json);
  EXPECT_EQ(json["pass"].get<bool>(), e.pass);
  EXPECT_DOUBLE_EQ(json["left"]["overlay_rms_px"].get<double>(), e.left.overlay_rms_px);

  // Same key: nothing is redone (the capture's images may even be gone).
  fs::remove_all(cache / "capture");
  auto second = run_calibration_pipeline(options);
  ASSERT_TRUE(second.ok()) << second.error().message;
  EXPECT_TRUE(second->cached);
  EXPECT_FALSE(fs::exists(cache / "capture"));
  EXPECT_EQ(second->evaluation.json, e.json);
  EXPECT_EQ(second->evaluation.left.fx_error_percent, e.left.fx_error_percent);
  EXPECT_EQ(second->evaluation.right.registration_mm, e.right.registration_mm);
  EXPECT_EQ(second->registered_file, first->registered_file);
}

TEST(CalibrationPipeline, ABadRigPathIsAnErrorNamingTheStepAndTheFile) {
  test_files::TempDir tmp("pipeline_bad");
  CalibrationPipelineOptions options = small_pipeline(tmp.file("cache"));
  options.rig_file = "/nonexistent/rig.yaml";
  auto result = run_calibration_pipeline(options);
  ASSERT_FALSE(result.ok());
  EXPECT_THAT(result.error().message,
              ::testing::StartsWith("calibration pipeline: capture: the rig file "
                                    "'/nonexistent/rig.yaml' does not exist"));

  options = small_pipeline(tmp.file("cache"));
  options.views = 0;
  result = run_calibration_pipeline(options);
  ASSERT_FALSE(result.ok());
  EXPECT_THAT(result.error().message, ::testing::HasSubstr("views 0 is outside 1..100"));
}

}  // namespace
}  // namespace telear::lab
