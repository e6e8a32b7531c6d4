#include "apps/console_command.hpp"

#include "telear/console/console_app.hpp"
#include "telear/lab/embedded_servers.hpp"

namespace telear::cli {
namespace {

// The embedded default behind the console: lab's simulated robot and stereo rig, as the
// console's LocalServers.
class SimulatedLocalServers : public console::LocalServers {
 public:
  explicit SimulatedLocalServers(std::unique_ptr<lab::EmbeddedServers> servers)
      : servers_(std::move(servers)) {}
  std::string robot_address() const override { return servers_->robot_address(); }
  std::string vision_address() const override { return servers_->vision_address(); }
  const std::string& token() const override { return servers_->token(); }
  const vision::StereoCameraModel& cameras() const override { return servers_->rig_cameras(); }
  void stop() override { servers_->stop(); }

 private:
  std::unique_ptr<lab::EmbeddedServers> servers_;
};

// The console's options as the flags name them: the library checks the same fields, but its
// messages name fields, not flags.
std::string flag_error(const console::ConsoleOptions& options) {
  if (options.robot.empty() != options.vision.empty())
    return "give both --robot and --vision, or neither (the embedded simulated servers)";
  if (!options.fullscreen_eyes.empty() && options.fullscreen_eyes != "two-windows" &&
      options.fullscreen_eyes != "sbs")
    return "--fullscreen-eyes '" + options.fullscreen_eyes + "': two-windows or sbs";
  if (options.headless && !options.fullscreen_eyes.empty())
    return "--fullscreen-eyes needs a display; it cannot be combined with --headless";
  if (options.frames < 0) return "--frames must be >= 0";
  if (options.headless && options.frames == 0 && options.script.empty() &&
      options.screenshot.empty())
    return "--headless needs --frames N or --script FILE (nothing would end it)";
  return {};
}

}  // namespace

console::LocalServersStarter simulated_local_servers() {
  return [](core::RobotModelPtr model, const core::RobotDescription& description,
            const std::string& calibration_file,
            const std::string& token) -> Result<std::unique_ptr<console::LocalServers>> {
    lab::EmbeddedServersOptions options;
    options.calibration_file = calibration_file;
    options.token = token;
    if (Status s = lab::serve_robot(options, description); !s) return s.error();
    auto servers = lab::EmbeddedServers::create(std::move(model), options);
    if (!servers) return servers.error();
    return std::unique_ptr<console::LocalServers>(
        std::make_unique<SimulatedLocalServers>(std::move(*servers)));
  };
}

int run_console(const console::ConsoleOptions& given, const geometry::RobotSelection& arm,
                std::ostream& out, std::ostream& err) {
  console::ConsoleOptions options = given;
  options.arm = arm.robot_spec();
  auto geometry = arm.geometry_options();
  if (!geometry) {
    err << "telear console: " << geometry.error().message << "\n";
    return 2;
  }
  options.geometry = *geometry;
  if (const std::string error = flag_error(options); !error.empty()) {
    err << "telear console: " << error << "\n";
    return 2;
  }
  // A screenshot without a frame count: long enough for the video and the state to arrive.
  if (!options.screenshot.empty() && options.frames == 0) options.frames = 60;
  if (!options.start_local_servers) options.start_local_servers = simulated_local_servers();
  auto app = console::ConsoleApp::create(options, out);
  if (!app) {
    err << "telear console: " << app.error().message << "\n";
    return 2;
  }
  return (*app)->run();
}

int run_replay(const console::ReplayOptions& given, const geometry::RobotSelection& arm,
               std::ostream& out, std::ostream& err) {
  console::ReplayOptions options = given;
  options.arm = arm.robot_spec();
  auto geometry = arm.geometry_options();
  if (!geometry) {
    err << "telear replay: " << geometry.error().message << "\n";
    return 2;
  }
  options.geometry = *geometry;
  auto app = console::ReplayApp::create(options, out);
  if (!app) {
    err << "telear replay: " << app.error().message << "\n";
    return 2;
  }
  return (*app)->run();
}

}  // namespace telear::cli
