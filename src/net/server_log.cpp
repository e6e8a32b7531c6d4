#include "telear/net/server_log.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>

#include <memory>
#include <utility>

namespace telear::net {

namespace {

constexpr std::pair<const char*, spdlog::level::level_enum> kLevels[] = {
    {"trace", spdlog::level::trace}, {"debug", spdlog::level::debug}, {"info", spdlog::level::info},
    {"warn", spdlog::level::warn},   {"error", spdlog::level::err},   {"off", spdlog::level::off},
};

}  // namespace

Result<spdlog::level::level_enum> parse_log_level(const std::string& text) {
  std::string accepted;
  for (const auto& [name, level] : kLevels) {
    if (text == name) return level;
    accepted += accepted.empty() ? name : std::string(", ") + name;
  }
  return Error{"'" + text + "' is not a log level; use one of " + accepted};
}

void log_to_stderr(const std::string& name, spdlog::level::level_enum level) {
  auto logger = std::make_shared<spdlog::logger>(
      name, std::make_shared<spdlog::sinks::stderr_color_sink_mt>());
  logger->set_level(level);
  spdlog::set_default_logger(std::move(logger));
}

}  // namespace telear::net
