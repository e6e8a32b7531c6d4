#pragma once
// `telear console`: the operator console (docs/console.md). With no server addresses it starts
// the embedded simulated robot and vision servers and connects to them; with --robot,
// --vision and --token-file it connects to real ones. --headless renders into an EGL frame
// buffer with no window; --screenshot / --frames / --script automate it.

#include <ostream>

#include "telear/console/console_options.hpp"
#include "telear/console/local_servers.hpp"
#include "telear/console/replay_app.hpp"
#include "telear/geometry/robot_selection.hpp"

namespace telear::cli {

// The embedded default: lab's simulated robot and vision servers for the console's arm, on
// loopback (the console links no simulator; this is where the command wires it in).
console::LocalServersStarter simulated_local_servers();

// `arm`: --arm (the console's --robot is the server's address), --tip, --package-path,
// --missing-meshes.
int run_console(const console::ConsoleOptions& options, const geometry::RobotSelection& arm,
                std::ostream& out, std::ostream& err);

// `telear replay F.mcap` (console/replay_app.hpp). `arm`: --robot (empty: the recording's),
// --tip, --package-path, --missing-meshes. Exit 0, 1 when the screenshot failed, 2 on bad
// options or a recording that does not open.
int run_replay(const console::ReplayOptions& options, const geometry::RobotSelection& arm,
               std::ostream& out, std::ostream& err);

}  // namespace telear::cli
