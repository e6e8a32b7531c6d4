#include "telear/core/robot_loader.hpp"

#include <cstdlib>
#include <filesystem>

namespace telear::core {
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

}  // namespace telear::core
