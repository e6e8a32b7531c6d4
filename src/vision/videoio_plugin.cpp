// libtelear_videoio.so (telear/vision/videoio.hpp): the sources and the writer that need
// OpenCV's videoio, behind one table of functions.
#include "mp4_writer.hpp"
#include "telear/core/version.hpp"
#include "videoio_plugin_api.hpp"

namespace telear::vision {
namespace {

Result<std::unique_ptr<StereoSource>> open_files(const VideoFileSourceOptions& options) {
  auto opened = VideoFileSource::open(options);
  if (!opened) return opened.error();
  return std::unique_ptr<StereoSource>(std::move(*opened));
}

Result<std::unique_ptr<StereoSource>> open_cameras(const CameraSourceOptions& options) {
  auto opened = CameraSource::open(options);
  if (!opened) return opened.error();
  return std::unique_ptr<StereoSource>(std::move(*opened));
}

constexpr std::string_view kVersion = core::version();

const VideoioPluginApi kApi{kVersion.data(), sizeof(VideoioPluginApi), &open_files, &open_cameras,
                            &open_opencv_mp4_writer};

}  // namespace
}  // namespace telear::vision

extern "C" __attribute__((visibility("default"))) const telear::vision::VideoioPluginApi*
telear_videoio_plugin() {
  return &telear::vision::kApi;
}
