#pragma once
// What needs OpenCV's videoio -- a stereo pair of video files, a stereo pair of V4L2 cameras,
// an MP4 being written -- opened through the plugin libtelear_videoio.so, loaded at the first
// such call. videoio brings ~245 shared libraries (FFmpeg, GStreamer, and GDAL, Poppler, HDF5
// through imgcodecs); linked into a program, their dynamic linking was 0.15 s of every start
// (telear --version: 0.20 s against 0.05 s). Now only a program that opens a camera, a video
// file or an MP4 pays it, once.
//
// The plugin is looked for, in order: $TELEAR_VIDEOIO_PLUGIN (a path to the library), beside
// the running program's installed layout (<bindir>/../<libdir>/telear/), the build tree's
// copy, the install prefix's copy. It is built from the same sources as the program that loads
// it; a plugin of another telear version is refused.
#include <memory>
#include <string>

#include "telear/core/image.hpp"
#include "telear/core/result.hpp"
#include "telear/vision/camera_source.hpp"
#include "telear/vision/stereo_source.hpp"
#include "telear/vision/video_file_source.hpp"

namespace telear::vision {

struct VideoWriterOptions {
  std::string path;           // an .mp4 file
  int width = 0, height = 0;  // every frame's size, > 0
  double fps = 15.0;          // > 0
};

// A video file being written, one RGB8 frame at a time.
class VideoWriter {
 public:
  virtual ~VideoWriter() = default;
  // A frame of another size or format is an error, and nothing is written.
  virtual Status write(const core::Image& rgb) = 0;
  virtual std::string codec() const = 0;    // "avc1" (H.264) or "mp4v" (MPEG-4 part 2)
  virtual std::string warning() const = 0;  // why not H.264; empty when it is
  virtual void close() = 0;                 // finishes the file; later writes are errors
};

// Errors: the plugin's (it did not load: each place tried and why), else the source's own.
Result<std::unique_ptr<StereoSource>> open_video_file_pair(const VideoFileSourceOptions& options);
Result<std::unique_ptr<StereoSource>> open_camera_pair(const CameraSourceOptions& options);
// H.264 when OpenCV's FFmpeg can write it, else MPEG-4 part 2 (with a warning()); an error when
// neither opens.
Result<std::unique_ptr<VideoWriter>> open_mp4_writer(const VideoWriterOptions& options);

// The path of the loaded plugin (loading it if need be), or why it does not load.
Result<std::string> videoio_plugin_path();

}  // namespace telear::vision
