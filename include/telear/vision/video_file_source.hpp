#pragma once
// VideoFileSource: a stereo pair from two video files (one per eye) read with
// cv::VideoCapture (FFmpeg), looping at the end, paced at the file's frame rate. The same file
// for both eyes is fine (tests use Debian's opencv-doc vtest.avi).
//
// Frames are converted from OpenCV's BGR to RGB8. Both files must have the same frame size,
// unless `width`/`height` are given: then both are scaled to that size (INTER_AREA).

#include <memory>
#include <string>

#include "telear/vision/stereo_source.hpp"

namespace cv {
class VideoCapture;
}

namespace telear::vision {

struct VideoFileSourceOptions {
  std::string left_path, right_path;
  double fps = 0.0;           // 0: the left file's frame rate (30 when the file has none)
  int width = 0, height = 0;  // 0: the files' size
};

class VideoFileSource final : public StereoSource {
 public:
  // Errors: a file that does not exist or does not open as a video, sizes that differ.
  static Result<std::unique_ptr<VideoFileSource>> open(const VideoFileSourceOptions& options);
  ~VideoFileSource() override;

  std::string name() const override { return "files"; }
  int width() const override { return width_; }
  int height() const override { return height_; }
  double fps() const override { return fps_; }
  Result<StereoCapture> capture() override;

 private:
  VideoFileSource() = default;
  Result<core::Image> read_eye(cv::VideoCapture& video, const std::string& path);

  VideoFileSourceOptions options_;
  std::unique_ptr<cv::VideoCapture> left_, right_;
  int width_ = 0, height_ = 0;
  double fps_ = 30.0;
  std::unique_ptr<FramePacer> pacer_;
  std::uint64_t frame_ = 0;
};

}  // namespace telear::vision
