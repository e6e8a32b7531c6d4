#pragma once
// `telear web` (docs/web.md): the browser operator's server, on the embedded simulated
// servers unless --robot and --vision are given.

#include <ostream>

#include "telear/geometry/robot_selection.hpp"
#include "telear/web/web_options.hpp"

namespace telear::cli {

// Serves until SIGINT or SIGTERM. The first line on `out` is "listening on URL"; with the
// embedded servers the second is "token: T". Exit 2 when it cannot start (the reason on `err`).
int run_web(const web::WebOptions& options, const geometry::RobotSelection& arm, std::ostream& out,
            std::ostream& err);

}  // namespace telear::cli
