#pragma once
// A benchmark's --json FILE, opened before the run so that a bad path fails at once.

#include <fstream>
#include <optional>
#include <string>

namespace telear::cli {

// Opens `path` for writing into `file` when given; the error line when it cannot be.
inline std::optional<std::string> open_json_file(const std::string& path, std::ofstream& file) {
  if (path.empty()) return std::nullopt;
  file.open(path);
  if (!file) return "--json: cannot write '" + path + "'";
  return std::nullopt;
}

}  // namespace telear::cli
