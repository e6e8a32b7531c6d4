#include "telear/core/resource_uri.hpp"

#include <algorithm>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <system_error>

namespace telear::core {
namespace {

namespace fs = std::filesystem;

constexpr int kMaxPackageDepth = 3;
constexpr const char* kPackageHint = "set ROS_PACKAGE_PATH or add a package path";

bool is_dir(const fs::path& p) {
  std::error_code ec;
  return fs::is_directory(p, ec);
}

bool is_file(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

// Sub-directories of `dir`, sorted by name so that the search order does not depend on the
// file system's. Unreadable directories give none (a search path may hold anything).
std::vector<fs::path> sorted_subdirs(const fs::path& dir) {
  std::vector<fs::path> out;
  std::error_code ec;
  fs::directory_iterator it(dir, ec), end;
  for (; !ec && it != end; it.increment(ec)) {
    std::error_code type_ec;
    if (it->is_directory(type_ec) && !it->is_symlink(type_ec)) out.push_back(it->path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Rule 3 of the header: sub-directories at depth 1..3 named `package` holding a package.xml.
void search_depth(const fs::path& root, const std::string& package, std::vector<fs::path>& out) {
  std::deque<std::pair<fs::path, int>> queue{{root, 0}};
  while (!queue.empty()) {
    auto [dir, depth] = queue.front();
    queue.pop_front();
    if (depth >= kMaxPackageDepth) continue;
    for (const fs::path& sub : sorted_subdirs(dir)) {
      if (sub.filename() == package && is_file(sub / "package.xml")) out.push_back(sub);
      queue.emplace_back(sub, depth + 1);
    }
  }
}

std::string join_dirs(const std::vector<std::string>& items) {
  std::string s;
  for (const std::string& item : items) s += (s.empty() ? "" : ", ") + item;
  return s;
}

std::vector<std::string> all_dirs(const ResourceSearchPaths& search) {
  std::vector<std::string> dirs = search.package_paths;
  dirs.insert(dirs.end(), search.robot_package_paths.begin(), search.robot_package_paths.end());
  dirs.insert(dirs.end(), search.ros_package_path.begin(), search.ros_package_path.end());
  return dirs;
}

Result<std::string> existing(const std::string& what, const std::string& uri,
                             const fs::path& path) {
  if (is_file(path)) return fs::absolute(path).lexically_normal().string();
  return Error{what + " '" + uri + "' not found: " + path.string() + " does not exist"};
}

}  // namespace

std::vector<std::string> split_package_path(const std::string& value) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= value.size()) {
    const std::size_t colon = std::min(value.find(':', start), value.size());
    if (colon > start) out.push_back(value.substr(start, colon - start));
    start = colon + 1;
  }
  return out;
}

std::vector<std::string> ros_package_path_from_environment() {
  const char* value = std::getenv("ROS_PACKAGE_PATH");
  return value ? split_package_path(value) : std::vector<std::string>{};
}

std::vector<std::string> find_package_dirs(const std::string& package,
                                           const ResourceSearchPaths& search) {
  std::vector<fs::path> found;
  for (const std::string& d : all_dirs(search)) {
    const fs::path dir = fs::path(d).lexically_normal();
    if (is_dir(dir / package)) found.push_back(dir / package);
    const fs::path name = dir.has_filename() ? dir.filename() : dir.parent_path().filename();
    if (name == package && is_dir(dir)) found.push_back(dir);
    search_depth(dir, package, found);
  }
  std::vector<std::string> out;
  for (const fs::path& p : found) {
    const std::string s = p.lexically_normal().string();
    if (std::find(out.begin(), out.end(), s) == out.end()) out.push_back(s);
  }
  return out;
}

Result<std::string> resolve_resource_uri(const std::string& uri, const ResourceSearchPaths& search,
                                         const std::string& what) {
  const std::string kPackage = "package://", kFile = "file://";
  if (uri.empty()) return Error{what + " filename is empty"};
  if (uri.rfind(kPackage, 0) == 0) {
    const std::string rest = uri.substr(kPackage.size());
    const std::size_t slash = rest.find('/');
    if (slash == 0 || slash == std::string::npos || slash + 1 == rest.size()) {
      return Error{what + " '" + uri + "' is not a package URI of the form package://PKG/PATH"};
    }
    const std::string package = rest.substr(0, slash), relative = rest.substr(slash + 1);
    const std::vector<std::string> dirs = find_package_dirs(package, search);
    for (const std::string& dir : dirs) {
      if (is_file(fs::path(dir) / relative)) {
        return fs::absolute(fs::path(dir) / relative).lexically_normal().string();
      }
    }
    // Where we looked: every package directory found, else D/PKG for each search directory.
    std::vector<std::string> looked = dirs;
    if (looked.empty()) {
      for (const std::string& d : all_dirs(search)) {
        looked.push_back((fs::path(d) / package).lexically_normal().string());
      }
    }
    if (looked.empty()) {
      return Error{what + " '" + uri + "' not found (no package search path; " + kPackageHint +
                   ")"};
    }
    return Error{what + " '" + uri + "' not found (looked in " + join_dirs(looked) + "; " +
                 kPackageHint + ")"};
  }
  if (uri.rfind(kFile, 0) == 0) {
    const fs::path path = uri.substr(kFile.size());
    if (!path.is_absolute()) {
      return Error{what + " '" + uri + "' is not an absolute file:// URI (file:///PATH)"};
    }
    return existing(what, uri, path);
  }
  if (const std::size_t scheme = uri.find("://"); scheme != std::string::npos) {
    return Error{what + " '" + uri + "' has the unsupported scheme '" + uri.substr(0, scheme) +
                 "' (use package://, file:// or a path)"};
  }
  const fs::path path(uri);
  if (path.is_absolute()) return existing(what, uri, path);
  return existing(what, uri, fs::path(search.base_dir.empty() ? "." : search.base_dir) / path);
}

}  // namespace telear::core
