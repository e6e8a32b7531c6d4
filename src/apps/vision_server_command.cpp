#include "apps/vision_server_command.hpp"

#include <spdlog/spdlog.h>

#include <csignal>
#include <memory>
#include <optional>

#include "apps/command_failure.hpp"
#include "telear/core/image_size.hpp"
#include "telear/core/number_list.hpp"
#include "telear/lab/vision_source.hpp"
#include "telear/net/server_log.hpp"
#include "telear/net/vision_server.hpp"

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
  const CommandFailure fail{err, "telear vision-server"};
  // SIGINT / SIGTERM are taken by sigwait below: block them before any thread starts (every
  // thread inherits the mask), so no thread is interrupted and the main thread shuts down.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);

  auto log_level = net::parse_log_level(options.log_level);
  if (!log_level) return fail("--log-level " + log_level.error().message, 2);
  // The log (streams, clients, errors) goes to stderr: stdout carries only the ready line.
  net::log_to_stderr("vision-server", *log_level);

  auto resolution = parse_resolution(options.resolution);
  if (!resolution) return fail(resolution.error().message, 2);
  if (!(options.fps >= 0.0 && options.fps <= 1000.0)) return fail("--fps must be in [0, 1000]", 2);

  lab::VisionSourceOptions source_options;
  source_options.kind = options.source;
  source_options.rig = options.rig;
  source_options.robot_server = options.robot_server;
  source_options.robot_token_file =
      options.robot_token_file.empty() ? options.token_file : options.robot_token_file;
  source_options.left = options.left;
  source_options.right = options.right;
  source_options.fps = options.fps;
  source_options.size = *resolution;
  source_options.supersample = options.supersample;
  source_options.noise = options.noise;
  if (options.source == "v4l2") {
    auto indices = core::parse_number_list(options.cameras, "--cameras", 2);
    if (!indices) return fail(indices.error().message, 2);
    source_options.left_camera = static_cast<int>((*indices)[0]);
    source_options.right_camera = static_cast<int>((*indices)[1]);
  }
  // Outlives the server (declared first): the simulated rig reads the robot it follows.
  auto opened = lab::open_vision_source(source_options);
  if (!opened) {
    // A camera that does not open is a failure to start; anything else, a bad option.
    const bool device = options.source == "v4l2" && options.robot_server.empty();
    return fail(opened.error().message, device ? 1 : 2);
  }
  for (const std::string& warning : opened->warnings)
    err << "telear vision-server: " << warning << "\n";

  net::VisionServerOptions server_options;
  server_options.listen_address = options.listen;
  server_options.source = std::move(opened->source);
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
  if (opened->robot) opened->robot->stop();
  out << "vision server stopped: " << stats.captured << " pairs captured, " << stats.encoded
      << " encoded, " << stats.capture_errors << " capture errors" << std::endl;
  return 0;
}

}  // namespace telear::cli
