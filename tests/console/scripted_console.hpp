#pragma once
// The options every console test starts from: headless, on the embedded simulated servers as
// `telear console` starts them, a 320x240 live video, driven by a UI script and kept running
// after it (frames) until the test stops drawing.

#include <string>

#include "apps/console_command.hpp"
#include "telear/console/console_options.hpp"

namespace telear::test {

inline console::ConsoleOptions scripted_headless_console(const std::string& script, int width,
                                                         int height) {
  console::ConsoleOptions options;
  options.start_local_servers = cli::simulated_local_servers();  // as `telear console`
  options.headless = true;
  options.width = width;
  options.height = height;
  options.resolution = "320x240";
  options.script = script;
  options.frames = 1000000;
  return options;
}

}  // namespace telear::test
