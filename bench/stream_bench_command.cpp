#include "bench/stream_bench_command.hpp"

#include <spdlog/spdlog.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <ostream>
#include <sstream>
#include <vector>

#include "bench/json_file.hpp"
#include "bench/loopback_vision_server.hpp"
#include "bench/quiet_log.hpp"
#include "telear/core/clock.hpp"
#include "telear/core/image_size.hpp"
#include "telear/core/robot_loader.hpp"
#include "telear/core/trajectory.hpp"
#include "telear/net/command_bytes.hpp"
#include "telear/net/jpeg_codec.hpp"
#include "telear/net/latency_stages.hpp"
#include "telear/net/latency_summary.hpp"
#include "telear/net/robot_client.hpp"
#include "telear/net/robot_server.hpp"
#include "telear/net/vision_client.hpp"
#include "telear/net/vision_server.hpp"
#include "telear/sim/sim_robot_driver.hpp"
#include "telear/vision/synthetic_source.hpp"

namespace telear::cli {

namespace {

constexpr double kWarmupS = 0.5;
constexpr double kJogRateHz = 100.0;
constexpr double kMotionS = 10.0;

struct Resolution {
  int width = 0, height = 0;
};

// "640x480,1280x720" -> sizes; every item WIDTHxHEIGHT with 16..8192 per side.
Result<std::vector<Resolution>> parse_resolutions(const std::string& text) {
  std::vector<Resolution> sizes;
  std::stringstream items(text);
  std::string item;
  while (std::getline(items, item, ',')) {
    auto size = core::parse_image_size(item, {16, 16}, {8192, 8192});
    if (!size) return Error{"--resolutions: " + size.error().message};
    sizes.push_back(Resolution{size->width, size->height});
  }
  if (sizes.empty()) return Error{"--resolutions: no resolution given"};
  return sizes;
}

// The targets (docs/benchmarks.md); other sizes have none.
struct Target {
  double fps = 0.0;           // at least
  double total_p50_ms = 0.0;  // capture -> decoded at most
};

std::optional<Target> target_for(const Resolution& r) {
  if (r.width == 640 && r.height == 480) return Target{60.0, 30.0};
  if (r.width == 1280 && r.height == 720) return Target{30.0, 50.0};
  return std::nullopt;
}

using net::percentile;

struct Quantiles {
  double p50 = 0, p99 = 0;
};

Quantiles quantiles_ms(const std::vector<double>& seconds) {
  std::vector<double> ms(seconds.size());
  std::transform(seconds.begin(), seconds.end(), ms.begin(), [](double s) { return 1e3 * s; });
  if (ms.empty()) return {std::nan(""), std::nan("")};  // JSON null: nothing was measured
  return {percentile(ms, 50), percentile(ms, 99)};
}

double since_s(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// [SECTION] video

// The stages are net::kLatencyStages (telear/net/latency_stages.hpp), the total last.
using net::kLatencyStages;
constexpr int kStageCount = static_cast<int>(net::kLatencyStageCount);
constexpr int kTotalStage = static_cast<int>(net::kTotalLatencyStage);

struct VideoResult {
  Resolution size;
  double fps = 0;  // decoded per second at the client
  std::uint64_t frames = 0;
  std::uint64_t skipped_server = 0;  // source frames the server skipped for this client
  double bytes_per_frame = 0;        // whole StereoFrame message
  double jpeg_bytes_per_frame = 0;
  Quantiles stages[kStageCount];
  double codec_ms = 0;  // baseline: encode + decode of one pair, median
  std::optional<Target> target;
  bool fps_met() const { return target && fps >= target->fps; }
  bool latency_met() const { return target && stages[kTotalStage].p50 <= target->total_p50_ms; }
};

// The baseline: TurboJPEG encode + decode of both eyes of one synthetic pair on this thread,
// the median of `runs` (ms).
Result<double> codec_baseline_ms(const Resolution& size, int quality, int runs) {
  vision::SyntheticSourceOptions options;
  options.width = size.width;
  options.height = size.height;
  options.fps = 10000;  // the highest rate: no pacing to speak of
  options.distinct_frames = 1;
  auto source = vision::SyntheticSource::create(options);
  if (!source) return source.error();
  auto pair = (*source)->capture();
  if (!pair) return pair.error();
  net::JpegEncoder encoder;
  net::JpegDecoder decoder;
  std::vector<double> times;
  for (int i = 0; i < runs; ++i) {
    const std::int64_t start = core::monotonic_ns();
    for (const core::Image* eye : {&pair->left, &pair->right}) {
      auto jpeg = encoder.encode(*eye, quality);
      if (!jpeg) return jpeg.error();
      auto image = decoder.decode(*jpeg);
      if (!image) return image.error();
    }
    times.push_back(core::ns_to_s(core::monotonic_ns() - start));
  }
  return percentile(times, 50) * 1e3;
}

Result<VideoResult> measure_video(const Resolution& size, const StreamBenchOptions& options) {
  VideoResult result;
  result.size = size;
  result.target = target_for(size);
  auto baseline = codec_baseline_ms(size, options.quality, 20);
  if (!baseline) return baseline.error();
  result.codec_ms = *baseline;

  auto server =
      start_loopback_vision_server({size.width, size.height}, options.source_fps, options.quality);
  if (!server) return server.error();

  net::VisionClientOptions client_options;
  client_options.address = (*server)->address();
  client_options.client_name = "bench-stream";
  client_options.decode_eyes_in_parallel = !options.sequential_decode;
  client_options.decode_planes = options.decode_planes;
  net::VisionClient client(client_options);
  client.start();

  // Warm-up: connected, a few frames through, the clock offset estimated.
  const auto warmup_start = std::chrono::steady_clock::now();
  std::uint64_t after = 0;
  while (since_s(warmup_start) < kWarmupS || after == 0) {
    auto frame = client.wait_frame(after, 5.0);
    if (!frame) return Error{"no stereo frame from the vision server within 5 s"};
    after = frame->second;
  }

  net::LatencySeries stage_samples;
  double message_bytes = 0, jpeg_bytes = 0;
  const std::uint64_t decoded_before = client.frames_decoded();
  const auto start = std::chrono::steady_clock::now();
  while (since_s(start) < options.seconds) {
    auto frame = client.wait_frame(after, 1.0);
    if (!frame) continue;
    after = frame->second;
    const net::DecodedStereoFrame& f = *frame->first;
    stage_samples.add(f.latency);
    message_bytes += static_cast<double>(f.message_bytes);
    jpeg_bytes += static_cast<double>(f.jpeg_bytes);
    result.skipped_server += f.frames_skipped_server;
  }
  const double elapsed = since_s(start);
  result.frames = client.frames_decoded() - decoded_before;
  client.stop();
  (*server)->stop();

  result.fps = static_cast<double>(result.frames) / elapsed;
  const double seen = static_cast<double>(stage_samples.size());
  if (seen == 0) return Error{"no stereo frame decoded in the measured window"};
  result.bytes_per_frame = message_bytes / seen;
  result.jpeg_bytes_per_frame = jpeg_bytes / seen;
  for (int s = 0; s < kStageCount; ++s) result.stages[s] = quantiles_ms(stage_samples.seconds[s]);
  return result;
}

// [SECTION] robot

struct RobotResult {
  Quantiles ping_ms, set_gripper_ms;
  int calls = 0;
  net::CommandBytes bytes_100hz;         // plan sampled at the jog rate
  net::CommandBytes bytes_10hz;          // plan sampled at 10 Hz (still validates: same profile)
  std::uint64_t plan_message_bytes = 0;  // the plan itself (ExecutePlan, docs/trajectory.md)
  double motion_s = 0;
};

Result<RobotResult> measure_robot(const StreamBenchOptions& options) {
  RobotResult result;
  result.calls = options.rtt_calls;
  auto model = core::load_robot("puma560");
  if (!model) return model.error();
  auto driver = sim::SimRobotDriver::create(*model);
  if (!driver) return driver.error();
  net::RobotServerOptions server_options;
  server_options.listen_address = "127.0.0.1:0";
  server_options.token = "bench-token";
  auto server = net::RobotServer::create(std::move(*driver), std::move(server_options));
  if (!server) return server.error();

  net::RobotClientOptions client_options;
  client_options.address = (*server)->address();
  client_options.token = "bench-token";
  client_options.client_name = "bench-stream";
  net::RobotClient client(client_options);
  if (Status acquired = client.acquire_lease(); !acquired) return acquired.error();
  std::vector<double> ping, gripper;
  for (int i = 0; i < options.rtt_calls; ++i) {
    auto rtt = client.ping();
    if (!rtt) return rtt.error();
    ping.push_back(*rtt);
  }
  for (int i = 0; i < options.rtt_calls; ++i) {
    const std::int64_t start = core::monotonic_ns();
    if (Status set = client.set_gripper(i % 2 ? 0.6 : 0.4); !set) return set.error();
    gripper.push_back(core::ns_to_s(core::monotonic_ns() - start));
  }
  (void)client.release_lease();
  result.ping_ms = quantiles_ms(ping);
  result.set_gripper_ms = quantiles_ms(gripper);

  // The same 10 s motion both ways: every joint from the middle of its range by a quarter of
  // the range, one segment stretched to 10 s, timed by core.
  const core::RobotModel& robot = **model;
  Eigen::VectorXd q0(robot.dof()), q1(robot.dof());
  for (int i = 0; i < robot.dof(); ++i) {
    const core::JointLimits& limits = robot.joints()[i].limits;
    q0[i] = 0.5 * (limits.lower + limits.upper);
    q1[i] = q0[i] + 0.25 * (limits.upper - limits.lower);
  }
  auto trajectory = core::Trajectory::create(robot, {{q0}, core::JointWaypoint(q1, kMotionS)});
  if (!trajectory) return trajectory.error();
  result.motion_s = trajectory->duration();
  const std::string lease(32, '0');  // the server's lease ids are 32 characters
  auto at_100 = trajectory->sampled(kJogRateHz);
  if (!at_100) return at_100.error();
  auto at_10 = trajectory->sampled(10.0);
  if (!at_10) return at_10.error();
  result.bytes_100hz = net::compare_command_bytes(*at_100, kJogRateHz, lease, "plan-1");
  result.bytes_10hz = net::compare_command_bytes(*at_10, kJogRateHz, lease, "plan-1");
  auto message = net::plan_message_bytes(*trajectory, lease, "plan-1");
  if (!message) return message.error();
  result.plan_message_bytes = *message;
  return result;
}

// [SECTION] output

std::string format(const char* pattern, double value) {
  if (std::isnan(value)) return "-";
  char text[64];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

void print_video(const VideoResult& v, const StreamBenchOptions& options, std::ostream& out) {
  out << "\nstereo " << core::to_string(core::ImageSize{v.size.width, v.size.height})
      << " (synthetic source at " << format("%.0f", options.source_fps) << " fps, JPEG quality "
      << options.quality << (options.decode_planes ? ", decoded to Y'CbCr planes" : "")
      << (options.sequential_decode ? ", eyes decoded in turn" : "") << ")\n";
  out << "| figure | p50 | p99 | target | met |\n|---|---|---|---|---|\n";
  const std::string fps_target = v.target ? ">= " + format("%.0f", v.target->fps) + " fps" : "-";
  out << "| sustained decoded fps | " << format("%.1f", v.fps) << " | | " << fps_target << " | "
      << (v.target ? (v.fps_met() ? "PASS" : "MISS") : "-") << " |\n";
  for (int s = 0; s < kStageCount; ++s) {
    const bool total = s == kTotalStage;
    std::string target = "-", met = "-";
    if (total && v.target) {
      target = "p50 <= " + format("%.0f", v.target->total_p50_ms) + " ms";
      met = v.latency_met() ? "PASS" : "MISS";
    }
    out << "| " << kLatencyStages[s].long_label << " (ms) | " << format("%.2f", v.stages[s].p50)
        << " | " << format("%.2f", v.stages[s].p99) << " | " << target << " | " << met << " |\n";
  }
  out << "| bytes per frame (message; JPEG both eyes) | " << format("%.0f", v.bytes_per_frame)
      << "; " << format("%.0f", v.jpeg_bytes_per_frame) << " | | | |\n";
  out << "baseline: TurboJPEG encode + decode of one stereo pair on one thread "
      << format("%.2f", v.codec_ms)
      << " ms; total p50 = " << format("%.1f", v.stages[kTotalStage].p50 / v.codec_ms)
      << " x codec time; " << v.frames << " frames decoded, " << v.skipped_server
      << " source frames skipped for this client by the server\n";
}

void print_robot(const RobotResult& r, std::ostream& out) {
  out << "\nrobot commands (RobotClient -> RobotServer, simulated driver, lease held, " << r.calls
      << " calls each)\n";
  out << "| round trip | p50 (ms) | p99 (ms) |\n|---|---|---|\n";
  out << "| Ping | " << format("%.3f", r.ping_ms.p50) << " | " << format("%.3f", r.ping_ms.p99)
      << " |\n";
  out << "| SetGripper | " << format("%.3f", r.set_gripper_ms.p50) << " | "
      << format("%.3f", r.set_gripper_ms.p99) << " |\n";
  out << "\nthe same " << format("%.1f", r.motion_s)
      << " s motion: plan-then-send vs streaming jog at 100 Hz (serialized protobuf bytes)\n";
  out << "| command | messages | bytes | jog stream / this |\n|---|---|---|---|\n";
  const auto row = [&](const std::string& name, int messages, std::uint64_t bytes) {
    out << "| " << name << " | " << messages << " | " << bytes << " | "
        << format("%.1f",
                  static_cast<double>(r.bytes_100hz.jog_stream_bytes) / static_cast<double>(bytes))
        << " |\n";
  };
  row("ExecutePlan (the plan message)", 1, r.plan_message_bytes);
  row("ExecuteTrajectory, sampled at 100 Hz", 1, r.bytes_100hz.plan_bytes);
  row("ExecuteTrajectory, sampled at 10 Hz", 1, r.bytes_10hz.plan_bytes);
  row("Jog (joint target) at 100 Hz", r.bytes_100hz.jog_messages, r.bytes_100hz.jog_stream_bytes);
  out << "gRPC/HTTP2 framing comes on top: ~9 B + headers per message, once for the plan\n";
}

nlohmann::json to_json(const VideoResult& v) {
  auto number = [](double x) { return std::isnan(x) ? nlohmann::json() : nlohmann::json(x); };
  nlohmann::json j;
  j["width"] = v.size.width;
  j["height"] = v.size.height;
  j["fps"] = v.fps;
  j["frames"] = v.frames;
  j["frames_skipped_server"] = v.skipped_server;
  j["bytes_per_frame"] = v.bytes_per_frame;
  j["jpeg_bytes_per_frame"] = v.jpeg_bytes_per_frame;
  for (int s = 0; s < kStageCount; ++s) {
    j["latency_ms"][kLatencyStages[s].key] = {{"p50", number(v.stages[s].p50)},
                                              {"p99", number(v.stages[s].p99)}};
  }
  j["codec_baseline_ms"] = v.codec_ms;
  j["total_p50_over_codec"] = v.stages[kTotalStage].p50 / v.codec_ms;
  if (v.target) {
    j["target"] = {{"fps", v.target->fps}, {"total_p50_ms", v.target->total_p50_ms}};
    j["fps_met"] = v.fps_met();
    j["latency_met"] = v.latency_met();
  } else {
    j["target"] = nullptr;
  }
  return j;
}

nlohmann::json to_json(const RobotResult& r) {
  auto bytes = [](const net::CommandBytes& b) {
    return nlohmann::json{{"plan_bytes", b.plan_bytes},
                          {"jog_stream_bytes", b.jog_stream_bytes},
                          {"jog_messages", b.jog_messages}};
  };
  return {{"calls", r.calls},
          {"ping_ms", {{"p50", r.ping_ms.p50}, {"p99", r.ping_ms.p99}}},
          {"set_gripper_ms", {{"p50", r.set_gripper_ms.p50}, {"p99", r.set_gripper_ms.p99}}},
          {"motion_s", r.motion_s},
          {"jog_rate_hz", kJogRateHz},
          {"command_bytes_plan_100hz", bytes(r.bytes_100hz)},
          {"command_bytes_plan_10hz", bytes(r.bytes_10hz)},
          {"command_bytes_plan_message", r.plan_message_bytes}};
}

}  // namespace

int run_bench_stream(const StreamBenchOptions& options, std::ostream& out, std::ostream& err) {
  const auto fail = [&err](const std::string& message, int code) {
    err << "telear bench stream: " << message << "\n";
    return code;
  };
  if (!(options.seconds > 0 && options.seconds <= 600)) {
    return fail("--seconds must be in (0, 600], got " + format("%g", options.seconds), 2);
  }
  if (!(options.source_fps > 0 && options.source_fps <= 1000)) {
    return fail("--source-fps must be in (0, 1000], got " + format("%g", options.source_fps), 2);
  }
  if (options.quality < 1 || options.quality > 100) {
    return fail("--quality must be in 1..100, got " + std::to_string(options.quality), 2);
  }
  if (options.rtt_calls < 1 || options.rtt_calls > 1000000) {
    return fail("--rtt-calls must be in 1..1000000, got " + std::to_string(options.rtt_calls), 2);
  }
  auto sizes = parse_resolutions(options.resolutions);
  if (!sizes) return fail(sizes.error().message, 2);
  std::ofstream json_file;
  if (const auto error = open_json_file(options.json, json_file)) return fail(*error, 2);

  const QuietLog quiet;
  const auto wall_start = std::chrono::steady_clock::now();
  out << "telear bench stream: the real servers on 127.0.0.1, one client each, "
      << format("%g", options.seconds) << " s per resolution\n";
  std::vector<VideoResult> videos;
  for (const Resolution& size : *sizes) {
    auto video = measure_video(size, options);
    if (!video) return fail(video.error().message, 1);
    print_video(*video, options, out);
    videos.push_back(*video);
  }
  auto robot = measure_robot(options);
  if (!robot) return fail(robot.error().message, 1);
  print_robot(*robot, out);
  out << "ran in " << format("%.1f", since_s(wall_start)) << " s\n";

  if (json_file) {
    nlohmann::json j;
    j["seconds"] = options.seconds;
    j["source"] = "synthetic";
    j["source_fps"] = options.source_fps;
    j["jpeg_quality"] = options.quality;
    for (const VideoResult& v : videos) j["video"].push_back(to_json(v));
    j["robot"] = to_json(*robot);
    json_file << j.dump(2) << "\n";
  }
  return 0;
}

}  // namespace telear::cli
