#include "telear/vision/videoio.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <optional>
#include <string_view>
#include <vector>

#include "telear/core/version.hpp"
#include "videoio_plugin_api.hpp"
#include "videoio_plugin_paths.hpp"  // generated: kPluginBuildPath, kPluginInstallPath, ...

namespace telear::vision {
namespace {

namespace fs = std::filesystem;

struct LoadedPlugin {
  const VideoioPluginApi* api = nullptr;
  std::string path;
  std::string error;  // why it did not load, when api is null
};

// The places to look, in order (telear/vision/videoio.hpp).
std::vector<std::string> candidates() {
  std::vector<std::string> paths;
  std::error_code ec;
  const fs::path program = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    paths.emplace_back((program.parent_path() / kPluginFromBindir).lexically_normal().string());
  }
  // In place: a moved temporary std::string trips GCC 12's -Warray-bounds false positive.
  paths.emplace_back(kPluginBuildPath);
  paths.emplace_back(kPluginInstallPath);
  return paths;
}

// Loads `path`; on failure, why (the plugin's own dlerror names a missing library or symbol).
std::optional<std::string> try_load(const std::string& path, LoadedPlugin& loaded) {
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) return std::string(dlerror());
  auto entry =
      reinterpret_cast<TelearVideoioPluginFunction>(dlsym(handle, "telear_videoio_plugin"));
  if (entry == nullptr) {
    dlclose(handle);
    return std::string("no telear_videoio_plugin symbol: not telear's videoio plugin");
  }
  const VideoioPluginApi* api = entry();
  if (api == nullptr || std::string_view(api->version) != core::version() ||
      api->size != sizeof(VideoioPluginApi)) {
    const std::string theirs = api != nullptr ? api->version : "none";
    dlclose(handle);
    return "a plugin of telear " + theirs + ", not " + std::string(core::version());
  }
  loaded.api = api;
  loaded.path = path;
  return std::nullopt;  // the handle stays open for the program's life
}

const LoadedPlugin& plugin() {
  static LoadedPlugin loaded;
  static std::once_flag once;
  std::call_once(once, [] {
    if (const char* chosen = std::getenv("TELEAR_VIDEOIO_PLUGIN"); chosen && *chosen) {
      if (auto why = try_load(chosen, loaded)) {
        loaded.error = "the videoio plugin TELEAR_VIDEOIO_PLUGIN='" + std::string(chosen) +
                       "' does not load: " + *why;
      }
      return;
    }
    std::string tried;
    for (const std::string& path : candidates()) {
      std::error_code ec;
      std::optional<std::string> why;
      if (!fs::is_regular_file(path, ec)) {
        why = "not found";
      } else {
        why = try_load(path, loaded);
      }
      if (!why) return;
      tried += (tried.empty() ? "" : "; ") + path + ": " + *why;
    }
    loaded.error =
        "the videoio plugin (libtelear_videoio.so, for cameras, video files and MP4) does not "
        "load (" +
        tried + "); set TELEAR_VIDEOIO_PLUGIN to its path";
  });
  return loaded;
}

}  // namespace

Result<std::string> videoio_plugin_path() {
  const LoadedPlugin& p = plugin();
  if (p.api == nullptr) return Error{p.error};
  return p.path;
}

Result<std::unique_ptr<StereoSource>> open_video_file_pair(const VideoFileSourceOptions& options) {
  const LoadedPlugin& p = plugin();
  if (p.api == nullptr) return Error{p.error};
  return p.api->open_video_file_pair(options);
}

Result<std::unique_ptr<StereoSource>> open_camera_pair(const CameraSourceOptions& options) {
  const LoadedPlugin& p = plugin();
  if (p.api == nullptr) return Error{p.error};
  return p.api->open_camera_pair(options);
}

Result<std::unique_ptr<VideoWriter>> open_mp4_writer(const VideoWriterOptions& options) {
  const LoadedPlugin& p = plugin();
  if (p.api == nullptr) return Error{p.error};
  return p.api->open_mp4_writer(options);
}

}  // namespace telear::vision
