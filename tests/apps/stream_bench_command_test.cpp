// `telear bench stream`: a short run at a small size through the real servers on loopback;
// the table and JSON have their fields and frames flowed. Timings are printed, never asserted.

#include "bench/stream_bench_command.hpp"

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

TEST(StreamBenchCommandTest, ShortRunWritesTheTableAndJson) {
  test_files::TempDir tmp("stream_bench");
  const std::filesystem::path json_path = tmp.file("bench.json");
  StreamBenchOptions options;
  options.seconds = 0.3;
  options.resolutions = "64x48";
  options.rtt_calls = 5;
  options.json = json_path.string();
  std::ostringstream out, err;
  ASSERT_EQ(run_bench_stream(options, out, err), 0) << err.str();
  EXPECT_THAT(out.str(), HasSubstr("stereo 64x48"));
  EXPECT_THAT(out.str(), HasSubstr("| total capture -> decoded (ms) |"));
  EXPECT_THAT(out.str(), HasSubstr("| SetGripper |"));
  EXPECT_THAT(out.str(), HasSubstr("| Jog (joint target) at 100 Hz |"));

  std::ifstream in(json_path);
  ASSERT_TRUE(in) << json_path;
  const nlohmann::json j = nlohmann::json::parse(in);
  ASSERT_EQ(j.at("video").size(), 1u);
  const nlohmann::json& video = j["video"][0];
  EXPECT_EQ(video.at("width"), 64);
  EXPECT_GT(video.at("fps").get<double>(), 0.0);
  EXPECT_GT(video.at("bytes_per_frame").get<double>(), 0.0);
  for (const char* stage :
       {"capture_to_encode", "encode", "send_queue", "network", "decode", "total"}) {
    EXPECT_TRUE(video.at("latency_ms").at(stage).contains("p50")) << stage;
    EXPECT_TRUE(video.at("latency_ms").at(stage).contains("p99")) << stage;
  }
  EXPECT_GT(video.at("codec_baseline_ms").get<double>(), 0.0);
  EXPECT_TRUE(video.at("target").is_null());  // no target at this size
  const nlohmann::json& robot = j.at("robot");
  EXPECT_EQ(robot.at("calls"), 5);
  EXPECT_TRUE(robot.at("ping_ms").contains("p99"));
  EXPECT_TRUE(robot.at("set_gripper_ms").contains("p50"));
  const nlohmann::json& bytes = robot.at("command_bytes_plan_100hz");
  EXPECT_GT(bytes.at("jog_stream_bytes").get<double>(), bytes.at("plan_bytes").get<double>());
  EXPECT_GE(robot.at("motion_s").get<double>(), 10.0);
}

TEST(StreamBenchCommandTest, BadArgumentsGetOneClearLine) {
  std::ostringstream out, err;
  StreamBenchOptions bad_seconds;
  bad_seconds.seconds = 0;
  EXPECT_EQ(run_bench_stream(bad_seconds, out, err), 2);
  EXPECT_EQ(err.str(), "telear bench stream: --seconds must be in (0, 600], got 0\n");
  err.str("");
  StreamBenchOptions bad_size;
  bad_size.resolutions = "640x480,big";
  EXPECT_EQ(run_bench_stream(bad_size, out, err), 2);
  EXPECT_EQ(err.str(),
            "telear bench stream: --resolutions: 'big' is not WIDTHxHEIGHT (e.g. 640x480)\n");
}

}  // namespace
}  // namespace telear::cli
