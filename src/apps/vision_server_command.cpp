#include "apps/vision_server_command.hpp"

#include <spdlog/spdlog.h>

#include <csignal>
#include <memory>
#include <optional>

#include "telear/core/image_size.hpp"
#include "telear/core/number_list.hpp"
#include "telear/net/bearer_auth.hpp"
#include "telear/net/robot_client.hpp"
#include "telear/net/server_log.hpp"
#include "telear/net/vision_server.hpp"
#include "telear/sim/sim_rig_source.hpp"
#include "telear/vision/camera_source.hpp"
#include "telear/vision/synthetic_source.hpp"
#include "telear/vision/video_file_source.hpp"

namespace telear::cli {
namespace {

// An empty --resolution keeps the source's own size.
Result<std::optional<core::ImageSize>> parse_resolution(const std::string& text) {
  if (text.empty()) return std::optional<core::ImageSize>{};
  auto size = core::parse_image_size(text, {16, 16}, {8192, 8192});
  if (!size) return Error{"--resolution: " + size.error().message};
  return std::optional<core::ImageSize>(*size);
}

}  // namespace

int run_vision_server(const VisionServerCommandOptions& options, std::ostream& out,
                      std::ostream& err) {
  auto fail = [&err](const std::string& message, int code) {
    err << "telear vision-server: " << message << "\n";
    return code;
  };
  // SIGINT / SIGTERM are taken by sigwait below: block them before any thread starts (every
  // thread inherits the mask), so no thread is interrupted and the main thread shuts down.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);

  auto log_level = net::parse_log_level(options.log_level);
  if (!log_level) return fail(log_level.error().message, 2);
  // The log (streams, clients, errors) goes to stderr: stdout carries only the ready line.
  net::log_to_stderr("vision-server", *log_level);

  auto resolution = parse_resolution(options.resolution);
  if (!resolution) return fail(resolution.error().message, 2);
  if (!(options.fps >= 0.0 && options.fps <= 1000.0)) return fail("--fps must be in [0, 1000]", 2);
  if (!options.robot_server.empty() && options.source != "sim") {
    return fail("--robot-server is for --source sim (the simulated rig follows the robot)", 2);
  }

  // The robot the simulated rig follows; outlives the server (declared first).
  std::unique_ptr<net::RobotClient> robot;
  std::unique_ptr<vision::StereoSource> source;
  if (options.source == "sim") {
    sim::SimRigSourceOptions sim;
    sim.rig = options.rig;
    if (options.fps > 0) sim.fps = options.fps;
    sim.supersample = options.supersample;
    sim.noise_sigma = options.noise;
    if (resolution->has_value()) {
      err << "telear vision-server: --resolution is ignored for --source sim (the rig file sets "
             "the cameras' size); clients may ask for a scaled stream\n";
    }
    if (!options.robot_server.empty()) {
      net::RobotClientOptions robot_options;
      robot_options.address = options.robot_server;
      robot_options.client_name = "telear-vision-server";
      const std::string& token_file =
          options.robot_token_file.empty() ? options.token_file : options.robot_token_file;
      if (!token_file.empty()) {
        auto token = net::load_token_file(token_file);
        if (!token) return fail(token.error().message, 2);
        robot_options.token = *token;
      }
      robot = std::make_unique<net::RobotClient>(robot_options);
      robot->start();
      sim.scene_state = [client = robot.get()]() -> std::optional<vision::SceneState> {
        auto sample = client->latest_state();
        if (!sample) return std::nullopt;
        return vision::SceneState{sample->state.q, sample->state.gripper,
                                  sample->capture_client_ns()};
      };
    }
    auto created = sim::SimRigSource::create(std::move(sim));
    if (!created) return fail(created.error().message, 2);
    source = std::move(*created);
  } else if (options.source == "files") {
    if (options.left.empty() || options.right.empty()) {
      return fail("--source files needs --left FILE and --right FILE", 2);
    }
    vision::VideoFileSourceOptions files{options.left, options.right, options.fps, 0, 0};
    if (resolution->has_value()) {
      files.width = (*resolution)->width;
      files.height = (*resolution)->height;
    }
    auto opened = vision::VideoFileSource::open(files);
    if (!opened) return fail(opened.error().message, 2);
    source = std::move(*opened);
  } else if (options.source == "v4l2") {
    auto indices = core::parse_number_list(options.cameras, "--cameras", 2);
    if (!indices) return fail(indices.error().message, 2);
    vision::CameraSourceOptions cameras;
    cameras.left_index = static_cast<int>((*indices)[0]);
    cameras.right_index = static_cast<int>((*indices)[1]);
    if (resolution->has_value()) {
      cameras.width = (*resolution)->width;
      cameras.height = (*resolution)->height;
    }
    if (options.fps > 0) cameras.fps = options.fps;
    auto opened = vision::CameraSource::open(cameras);
    if (!opened) return fail(opened.error().message, 1);
    source = std::move(*opened);
  } else if (options.source == "synthetic") {
    vision::SyntheticSourceOptions synthetic;
    if (resolution->has_value()) {
      synthetic.width = (*resolution)->width;
      synthetic.height = (*resolution)->height;
    }
    if (options.fps > 0) synthetic.fps = options.fps;
    auto created = vision::SyntheticSource::create(synthetic);
    if (!created) return fail(created.error().message, 2);
    source = std::move(*created);
  } else {
    return fail("--source '" + options.source + "' is not one of sim, files, v4l2, synthetic", 2);
  }

  net::VisionServerOptions server_options;
  server_options.listen_address = options.listen;
  server_options.source = std::move(source);
  server_options.calibration_file = options.calibration;
  server_options.token_file = options.token_file;
  server_options.jpeg_quality = options.quality;
  auto server = net::VisionServer::create(std::move(server_options));
  if (!server) return fail(server.error().message, 1);
  out << "vision server listening on " << (*server)->address() << std::endl;

  int signal_number = 0;
  sigwait(&signals, &signal_number);
  spdlog::info("{}, shutting down", signal_number == SIGINT ? "SIGINT" : "SIGTERM");
  const auto stats = (*server)->pipeline().stats();
  (*server)->stop();
  if (robot) robot->stop();
  out << "vision server stopped: " << stats.captured << " pairs captured, " << stats.encoded
      << " encoded, " << stats.capture_errors << " capture errors" << std::endl;
  return 0;
}

}  // namespace telear::cli
