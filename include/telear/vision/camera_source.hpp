#pragma once
// CameraSource: a stereo pair of V4L2 cameras (/dev/videoL, /dev/videoR) read through
// cv::VideoCapture(index, cv::CAP_V4L2), BGR converted to RGB8.
//
// The two cameras are not hardware-synchronized: each eye keeps its own capture time (the
// moment its grab() returned), and both are grabbed back to back before either is decoded
// (retrieve()) so the two exposures are as close as the driver allows. capture() is paced by
// the cameras themselves (grab() blocks until the driver has a frame).

#include <memory>
#include <string>

#include "telear/vision/stereo_source.hpp"

namespace cv {
class VideoCapture;
}

namespace telear::vision {

struct CameraSourceOptions {
  int left_index = 0, right_index = 1;  // /dev/video<index>
  int width = 640, height = 480;        // requested of the driver (it may pick another size)
  double fps = 30.0;                    // requested of the driver
};

class CameraSource final : public StereoSource {
 public:
  // Errors: "no camera at /dev/videoN: <why>" when a device is missing or will not open.
  static Result<std::unique_ptr<CameraSource>> open(const CameraSourceOptions& options);
  ~CameraSource() override;

  std::string name() const override { return "v4l2"; }
  int width() const override { return width_; }
  int height() const override { return height_; }
  double fps() const override { return fps_; }
  Result<StereoCapture> capture() override;

 private:
  CameraSource() = default;
  CameraSourceOptions options_;
  std::unique_ptr<cv::VideoCapture> left_, right_;
  int width_ = 0, height_ = 0;
  double fps_ = 30.0;
  std::uint64_t frame_ = 0;
};

}  // namespace telear::vision
