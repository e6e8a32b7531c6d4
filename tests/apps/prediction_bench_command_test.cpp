// `telear bench prediction` (issue 23): a short run -- one move at full speed under 400 ms of
// delay through the embedded simulated servers -- writes the table and the JSON keys, and the
// predicted arm is closer to the simulator's truth than the delayed reported arm. The goal's
// figures (docs/benchmarks.md) are printed, never asserted.

#include "bench/prediction_bench_command.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "test_util/temp_dir.hpp"

namespace telear::cli {
namespace {

using ::testing::HasSubstr;

TEST(PredictionBenchCommandTest, AShortRunPredictsCloserToTheTruthThanTheDelayedState) {
  test_files::TempDir tmp("prediction_bench");
  const std::filesystem::path json_path = tmp.file("bench.json");
  PredictionBenchOptions options;
  options.moves = 1;
  options.speed = 1.0;
  options.json = json_path.string();
  std::ostringstream out, err;
  ASSERT_EQ(run_bench_prediction(options, out, err), 0) << err.str();
  std::cout << out.str();
  EXPECT_THAT(out.str(), HasSubstr("| predicted (Smith) |"));
  EXPECT_THAT(out.str(), HasSubstr("| without prediction (last reported state) |"));

  std::ifstream in(json_path);
  ASSERT_TRUE(in) << json_path;
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j.at("delay_ms"), 400);
  EXPECT_EQ(j.at("execution"), "completed");
  const int frames = j.at("frames").get<int>();
  EXPECT_GT(frames, 10);
  // The delayed report shows the arm at rest for the first 400 ms, and the plan has no
  // trajectory to follow once the arm has stopped: most, not all, frames draw a prediction.
  EXPECT_GT(j.at("frames_predicted").get<int>(), frames / 2);
  for (const char* key : {"tool_error_mm_p50_predicted", "tool_error_mm_p95_predicted",
                          "tool_error_mm_p50_unpredicted", "tool_error_mm_p95_unpredicted"}) {
    EXPECT_TRUE(j.at(key).is_number()) << key;
  }
  EXPECT_LT(j.at("tool_error_mm_p95_predicted").get<double>(),
            j.at("tool_error_mm_p95_unpredicted").get<double>());
  EXPECT_LT(j.at("tool_error_mm_p50_predicted").get<double>(),
            j.at("tool_error_mm_p50_unpredicted").get<double>());
}

TEST(PredictionBenchCommandTest, BadArgumentsGetOneClearLine) {
  std::ostringstream out, err;
  PredictionBenchOptions delay;
  delay.delay_ms = -1;
  EXPECT_EQ(run_bench_prediction(delay, out, err), 2);
  EXPECT_EQ(err.str(), "telear bench prediction: --delay-ms must be in 0..5000, got -1\n");
  err.str("");
  PredictionBenchOptions speed;
  speed.speed = 0;
  EXPECT_EQ(run_bench_prediction(speed, out, err), 2);
  EXPECT_EQ(err.str(), "telear bench prediction: --speed must be in (0, 1], got 0\n");
}

}  // namespace
}  // namespace telear::cli
