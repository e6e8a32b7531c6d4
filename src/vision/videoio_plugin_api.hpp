#pragma once
// The table of functions libtelear_videoio.so exports (telear/vision/videoio.hpp): the one
// symbol `telear_videoio_plugin`, with C linkage, returns it. The plugin and the program that
// loads it are built from the same sources; `version` (telear/core/version.hpp) and `size`
// (sizeof the table) must match.
#include <cstddef>
#include <memory>

#include "telear/vision/videoio.hpp"

namespace telear::vision {

struct VideoioPluginApi {
  const char* version;
  std::size_t size;
  Result<std::unique_ptr<StereoSource>> (*open_video_file_pair)(const VideoFileSourceOptions&);
  Result<std::unique_ptr<StereoSource>> (*open_camera_pair)(const CameraSourceOptions&);
  Result<std::unique_ptr<VideoWriter>> (*open_mp4_writer)(const VideoWriterOptions&);
};

}  // namespace telear::vision

extern "C" {
using TelearVideoioPluginFunction = const telear::vision::VideoioPluginApi* (*)();
}
