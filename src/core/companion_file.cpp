#include "telear/core/companion_file.hpp"

#include <filesystem>

#include "telear/core/robot_loader.hpp"

namespace telear::core {

std::string find_companion_file(const RobotModel& model, const std::string& suffix) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!model.source().empty()) {
    fs::path beside = fs::path(model.source());
    beside.replace_extension(suffix);
    if (fs::is_regular_file(beside, ec)) return beside.string();
  }
  const fs::path shipped = fs::path(companion_directory()) / (model.name() + suffix);
  if (fs::is_regular_file(shipped, ec)) return shipped.string();
  return {};
}

std::string companion_directory() {
  return (std::filesystem::path(data_directory()) / "robots").string();
}

}  // namespace telear::core
