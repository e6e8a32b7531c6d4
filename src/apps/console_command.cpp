#include "apps/console_command.hpp"

#include "telear/console/console_app.hpp"

namespace telear::cli {

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
  if (options.frames < 0) {
    err << "telear console: --frames must be >= 0\n";
    return 2;
  }
  // A screenshot without a frame count: long enough for the video and the state to arrive.
  if (!options.screenshot.empty() && options.frames == 0) options.frames = 60;
  if (options.headless && options.frames == 0 && options.script.empty()) {
    err << "telear console: --headless needs --frames N or --script FILE (nothing would end it)\n";
    return 2;
  }
  auto app = console::ConsoleApp::create(options, out);
  if (!app) {
    err << "telear console: " << app.error().message << "\n";
    return 2;
  }
  return (*app)->run();
}

}  // namespace telear::cli
