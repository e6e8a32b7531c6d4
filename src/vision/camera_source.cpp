#include "telear/vision/camera_source.hpp"

#include <filesystem>
#include <opencv2/videoio.hpp>

#include "telear/vision/opencv_frame.hpp"

namespace telear::vision {
namespace {

std::string device_path(int index) {
  return "/dev/video" + std::to_string(index);
}

Result<std::unique_ptr<cv::VideoCapture>> open_camera(int index, const CameraSourceOptions& o) {
  const std::string path = device_path(index);
  if (index < 0) return Error{"no camera at " + path + ": a camera index is 0 or more"};
  std::error_code ec;
  // Checked first so the message says what is wrong (OpenCV's own is only a log warning).
  if (!std::filesystem::exists(path, ec)) {
    return Error{"no camera at " + path +
                 ": the device does not exist (is the camera plugged in? "
                 "ls /dev/video*)"};
  }
  auto camera = std::make_unique<cv::VideoCapture>(index, cv::CAP_V4L2);
  if (!camera->isOpened()) {
    return Error{"no camera at " + path +
                 ": V4L2 cannot open it (in use by another program, no permission — "
                 "group 'video' — or not a capture device)"};
  }
  camera->set(cv::CAP_PROP_FRAME_WIDTH, o.width);
  camera->set(cv::CAP_PROP_FRAME_HEIGHT, o.height);
  camera->set(cv::CAP_PROP_FPS, o.fps);
  // Keep the driver's queue short: an old buffered frame is latency.
  camera->set(cv::CAP_PROP_BUFFERSIZE, 1);
  return camera;
}

}  // namespace

CameraSource::~CameraSource() = default;

Result<std::unique_ptr<CameraSource>> CameraSource::open(const CameraSourceOptions& options) {
  if (options.left_index == options.right_index) {
    return Error{"cameras: left and right are the same device " + device_path(options.left_index)};
  }
  std::unique_ptr<CameraSource> source(new CameraSource());
  source->options_ = options;
  auto left = open_camera(options.left_index, options);
  if (!left) return left.error();
  auto right = open_camera(options.right_index, options);
  if (!right) return right.error();
  source->left_ = std::move(*left);
  source->right_ = std::move(*right);
  // The size the left driver settled on is the source's; the right eye is scaled to it.
  source->width_ = static_cast<int>(source->left_->get(cv::CAP_PROP_FRAME_WIDTH));
  source->height_ = static_cast<int>(source->left_->get(cv::CAP_PROP_FRAME_HEIGHT));
  if (source->width_ <= 0 || source->height_ <= 0) {
    source->width_ = options.width;
    source->height_ = options.height;
  }
  const double fps = source->left_->get(cv::CAP_PROP_FPS);
  source->fps_ = fps > 0 ? fps : options.fps;
  return source;
}

Result<StereoCapture> CameraSource::capture() {
  StereoCapture out;
  const bool left_ok = left_->grab();
  out.capture_ns_left = core::monotonic_ns();
  const bool right_ok = right_->grab();
  out.capture_ns_right = core::monotonic_ns();
  if (!left_ok) return Error{"camera " + device_path(options_.left_index) + ": grab failed"};
  if (!right_ok) return Error{"camera " + device_path(options_.right_index) + ": grab failed"};
  cv::Mat left, right;
  if (!left_->retrieve(left) || !right_->retrieve(right)) {
    return Error{"cameras: retrieve failed after a successful grab"};
  }
  out.left = rgb_from_bgr(left, width_, height_);
  out.right = rgb_from_bgr(right, width_, height_);
  if (out.left.empty() || out.right.empty()) {
    return Error{"cameras: a frame is not 8-bit BGR or grey"};
  }
  out.frame_number = ++frame_;
  return out;
}

}  // namespace telear::vision
