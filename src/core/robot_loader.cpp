#include "telear/core/robot_loader.hpp"

#include <cstdlib>
#include <filesystem>

namespace telear::core {
namespace {

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

Result<RobotModelPtr> shared(Result<RobotModel> model) {
  if (!model) return model.error();
  return std::make_shared<const RobotModel>(std::move(model).value());
}

}  // namespace

std::string data_directory() {
  namespace fs = std::filesystem;
  if (const char* env = std::getenv("TELEAR_DATA_DIR"); env != nullptr && *env != '\0') return env;
  // An installed program: PREFIX/bin/telear beside PREFIX/share/telear/data (docs/install.md).
  // Resolved on every call, so a prefix moved after installation still works.
  std::error_code error;
  const fs::path exe = fs::read_symlink("/proc/self/exe", error);
  if (!error) {
    const fs::path installed = exe.parent_path().parent_path() / "share" / "telear" / "data";
    if (fs::is_directory(installed, error)) return installed.string();
  }
  // The build tree (tests, programs run from build/): the source tree's data/.
  return TELEAR_DEFAULT_DATA_DIR;
}

Result<RobotModelPtr> load_robot(const std::string& name_or_path) {
  namespace fs = std::filesystem;
  if (name_or_path.empty()) return Error{"no robot given: name one (e.g. puma560) or a file"};
  const bool looks_like_path = name_or_path.find('/') != std::string::npos ||
                               ends_with(name_or_path, ".yaml") ||
                               ends_with(name_or_path, ".yml") || ends_with(name_or_path, ".urdf");
  std::string path = name_or_path;
  if (!looks_like_path) {
    path = (fs::path(data_directory()) / "robots" / (name_or_path + ".yaml")).string();
    if (!fs::exists(path)) {
      return Error{"unknown robot '" + name_or_path + "': no " + path +
                   " (give a shipped name such as puma560, or a .yaml / .urdf file)"};
    }
  }
  if (!fs::exists(path)) return Error{"robot file '" + path + "' does not exist"};
  if (ends_with(path, ".urdf")) return shared(load_urdf_file(path));
  if (ends_with(path, ".yaml") || ends_with(path, ".yml")) return shared(load_dh_yaml_file(path));
  return Error{"robot file '" + path + "': unknown format (expected .urdf, .yaml or .yml)"};
}

}  // namespace telear::core
