#pragma once
// The servers' log: both servers (telear/net/robot_server.hpp, telear/net/vision_server.hpp),
// their services and the vision pipeline log through spdlog's default logger: connections and
// the client's name (telear/net/client_name.hpp), every robot command, stream open / close with
// frames sent and skipped, source and encode errors. The commands `telear robot-server` and
// `telear vision-server` send it to stderr (stdout carries only the ready line) at the level
// of --log-level.
//
// Levels, most to least verbose: trace, debug, info (the default), warn, error, off. At warn
// only refusals, lapsed leases and errors are written; info adds one line per command and per
// stream; debug adds skipped frames.

#include <spdlog/spdlog.h>

#include <string>

#include "telear/core/result.hpp"

namespace telear::net {

// "trace", "debug", "info", "warn", "error" or "off" (exactly these words); anything else is an
// error naming the value and the accepted words.
Result<spdlog::level::level_enum> parse_log_level(const std::string& text);

// Makes spdlog's default logger write to stderr, lines tagged `name`, at `level`.
void log_to_stderr(const std::string& name, spdlog::level::level_enum level);

}  // namespace telear::net
