// `telear bench latency`: a one-second run through the vision service and the headless AR view
// measures frames at the screen by their frame code; the JSON has its keys and every frame was
// shown no earlier than it was decoded. Timings are printed, never asserted.

#include "bench/latency_bench_command.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "test_util/temp_dir.hpp"

namespace telear::cli {
namespace {

using ::testing::HasSubstr;

TEST(LatencyBenchCommandTest, OneSecondMeasuresFramesAtTheScreenAfterTheyAreDecoded) {
  test_files::TempDir tmp("latency_bench");
  const std::filesystem::path json_path = tmp.file("latency.json");
  LatencyBenchOptions options;
  options.resolution = "320x240";
  options.seconds = 1.0;
  options.json = json_path.string();
  std::ostringstream out, err;
  ASSERT_EQ(run_bench_latency(options, out, err), 0) << err.str();
  EXPECT_THAT(out.str(), HasSubstr("| capture -> shown (frame code read back) |"));
  EXPECT_THAT(out.str(), HasSubstr("shown before decoded: 0"));

  std::ifstream in(json_path);
  ASSERT_TRUE(in) << json_path;
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j.at("width"), 320);
  EXPECT_GE(j.at("frames").get<int>(), 5);  // ~30 at the default 30 fps
  EXPECT_EQ(j.at("frames_unreadable"), 0);
  EXPECT_GE(j.at("frames_lost").get<int>(), 0);
  for (const char* figure : {"encoded", "received", "decoded", "shown"}) {
    for (const char* p : {"_ms_p50", "_ms_p99"}) {
      EXPECT_GT(j.at(std::string(figure) + p).get<double>(), 0.0) << figure << p;
    }
  }
  EXPECT_GE(j.at("shown_ms_p50").get<double>(), j.at("decoded_ms_p50").get<double>());
  ASSERT_EQ(j.at("per_frame").size(), j.at("frames").get<std::size_t>());
  for (const nlohmann::json& frame : j.at("per_frame")) {
    EXPECT_GE(frame.at("shown_ms").get<double>(), frame.at("decoded_ms").get<double>())
        << "frame " << frame.at("frame");
    // Received -> decoded is on the client's clock alone (the network stage straddles the
    // offset estimate's error, a few microseconds on loopback: not compared).
    EXPECT_GE(frame.at("decoded_ms").get<double>(), frame.at("received_ms").get<double>());
  }
  EXPECT_TRUE(j.at("target").is_null());  // the goal is set at 640x480
}

TEST(LatencyBenchCommandTest, BadArgumentsGetOneClearLine) {
  std::ostringstream out, err;
  LatencyBenchOptions small;
  small.resolution = "64x48";
  EXPECT_EQ(run_bench_latency(small, out, err), 2);
  EXPECT_EQ(err.str(),
            "telear bench latency: --resolution: the frame code needs at least 304x64 pixels, got "
            "64x48\n");
  err.str("");
  LatencyBenchOptions no_time;
  no_time.seconds = 0;
  EXPECT_EQ(run_bench_latency(no_time, out, err), 2);
  EXPECT_EQ(err.str(), "telear bench latency: --seconds must be in (0, 600], got 0\n");
}

}  // namespace
}  // namespace telear::cli
