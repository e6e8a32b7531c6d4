#include "telear/web/page_files.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "web_page_paths.hpp"  // generated: kPageFromBindir, kPageBuildPath, kPageInstallPath

namespace telear::web {

namespace fs = std::filesystem;

Result<std::string> find_page_root(const std::string& given) {
  std::vector<std::string> candidates;
  if (!given.empty()) {
    candidates.push_back(given);
  } else {
    if (const char* env = std::getenv("TELEAR_WEB_ROOT"); env != nullptr && *env != '\0') {
      candidates.emplace_back(env);
    } else {
      std::error_code ec;
      const fs::path program = fs::read_symlink("/proc/self/exe", ec);
      if (!ec) {
        candidates.push_back((program.parent_path() / kPageFromBindir).lexically_normal());
      }
      candidates.emplace_back(kPageBuildPath);
      candidates.emplace_back(kPageInstallPath);
    }
  }
  std::string looked;
  for (const std::string& candidate : candidates) {
    if (fs::is_regular_file(fs::path(candidate) / "index.html")) return candidate;
    looked += (looked.empty() ? "" : ", ") + candidate;
  }
  return Error{"the page's files (index.html, app.js) are not in " + looked +
               " (build them: scripts/build.sh bundles web/ into build/web; or set "
               "TELEAR_WEB_ROOT)"};
}

std::string content_type_of(const std::string& name) {
  const std::string extension = fs::path(name).extension().string();
  if (extension == ".html") return "text/html; charset=utf-8";
  if (extension == ".js" || extension == ".mjs") return "text/javascript; charset=utf-8";
  if (extension == ".css") return "text/css; charset=utf-8";
  if (extension == ".json" || extension == ".map") return "application/json";
  if (extension == ".png") return "image/png";
  if (extension == ".svg") return "image/svg+xml";
  if (extension == ".ico") return "image/x-icon";
  return "application/octet-stream";
}

std::optional<PageFile> read_page_file(const std::string& root, const std::string& target) {
  std::string path = target.substr(0, target.find_first_of("?#"));
  if (path.empty() || path.front() != '/') return std::nullopt;
  if (path == "/") path = "/index.html";
  // Only plain names below the root: no parent steps, no backslashes or NULs, no "//x"
  // that a join would read as absolute.
  if (path.find("..") != std::string::npos || path.find('\\') != std::string::npos ||
      path.find('\0') != std::string::npos || path.find("//") != std::string::npos) {
    return std::nullopt;
  }
  const fs::path file = fs::path(root) / path.substr(1);
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) return std::nullopt;
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream body;
  body << in.rdbuf();
  return PageFile{body.str(), content_type_of(file.filename().string())};
}

}  // namespace telear::web
