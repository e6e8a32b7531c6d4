#include "apps/vision_server_command.hpp"

#include <spdlog/spdlog.h>

#include <csignal>
#include <cstdlib>
#include <memory>
#include <optional>

#include "apps/command_failure.hpp"
#include "telear/core/image_size.hpp"
#include "telear/core/number_list.hpp"
#include "telear/drivers/ros1_stereo_source.hpp"
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

// The ros source is telear::drivers' (lab does not link it): lab calls this for it.
Result<lab::VisionSource> open_ros_source(const lab::VisionSourceOptions& options) {
  drivers::Ros1StereoSourceOptions ros;
  ros.master_uri = options.ros_master;
  ros.left_topic = options.left;
  ros.right_topic = options.right;
  ros.sync_tolerance_s = options.sync_tolerance_ms * 1e-3;
  ros.camera_info = options.camera_info;
  ros.fps = options.fps;
  auto opened = drivers::open_ros1_stereo_source(ros);
  if (!opened) return opened.error();
  lab::VisionSource source;
  source.source = std::move(opened->source);
  source.calibration_yaml = std::move(opened->calibration_yaml);
  source.warnings = std::move(opened->warnings);
  return source;
}

// The ros source's options, checked before its node starts (usage errors, exit 2).
Status check_ros_options(const VisionServerCommandOptions& options) {
  if (options.left.empty() || options.right.empty()) {
    return Error{
        "--source ros needs --left and --right, the cameras' image topics (e.g. "
        "/stereo/left/image_raw)"};
  }
  if (options.left == options.right) {
    return Error{"--left and --right name the same topic, " + options.left};
  }
  if (!(options.sync_tolerance_ms >= 0.0 && options.sync_tolerance_ms <= 1000.0)) {
    return Error{"--sync-tolerance-ms must be in [0, 1000]"};
  }
  std::string master = options.ros_master;
  if (const char* environment = std::getenv("ROS_MASTER_URI"); master.empty() && environment) {
    master = environment;
  }
  if (master.empty()) {
    return Error{
        "--source ros needs a ROS master: give --ros-master http://HOST:PORT or set "
        "ROS_MASTER_URI"};
  }
  if (master.rfind("http://", 0) != 0) {
    return Error{"--ros-master must look like http://HOST:PORT, got '" + master + "'"};
  }
  return Status::Ok();
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
  if (options.source == "ros") {
    if (Status ros = check_ros_options(options); !ros) return fail(ros.error().message, 2);
  }

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
  source_options.frame_code = options.frame_code;
  source_options.ros_master = options.ros_master;
  source_options.sync_tolerance_ms = options.sync_tolerance_ms;
  source_options.camera_info = options.calibration.empty();  // a file overrides camera_info
  source_options.open_ros = open_ros_source;
  if (options.source == "v4l2") {
    auto indices = core::parse_number_list(options.cameras, "--cameras", 2);
    if (!indices) return fail(indices.error().message, 2);
    source_options.left_camera = static_cast<int>((*indices)[0]);
    source_options.right_camera = static_cast<int>((*indices)[1]);
  }
  // Outlives the server (declared first): the simulated rig reads the robot it follows.
  auto opened = lab::open_vision_source(source_options);
  if (!opened) {
    // A camera (or camera topic) that does not open is a failure to start; anything else, a
    // bad option.
    const bool device =
        (options.source == "v4l2" || options.source == "ros") && options.robot_server.empty();
    return fail(opened.error().message, device ? 1 : 2);
  }
  for (const std::string& warning : opened->warnings)
    err << "telear vision-server: " << warning << "\n";

  net::VisionServerOptions server_options;
  server_options.listen_address = options.listen;
  server_options.source = std::move(opened->source);
  server_options.calibration_file = options.calibration;
  if (options.calibration.empty()) server_options.calibration_yaml = opened->calibration_yaml;
  server_options.token_file = options.token_file;
  server_options.observer_token_file = options.observer_token_file;
  server_options.tls_cert_file = options.tls_cert;
  server_options.tls_key_file = options.tls_key;
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
