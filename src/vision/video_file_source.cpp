#include "telear/vision/video_file_source.hpp"

#include <filesystem>
#include <opencv2/videoio.hpp>

#include "telear/core/image_size.hpp"
#include "telear/vision/opencv_frame.hpp"

namespace telear::vision {
namespace {

Result<std::unique_ptr<cv::VideoCapture>> open_video(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    return Error{"video file '" + path + "': no such file"};
  }
  auto video = std::make_unique<cv::VideoCapture>(path, cv::CAP_FFMPEG);
  if (!video->isOpened()) {
    return Error{"video file '" + path + "': not a video OpenCV (FFmpeg) can read"};
  }
  return video;
}

}  // namespace

VideoFileSource::~VideoFileSource() = default;

Result<std::unique_ptr<VideoFileSource>> VideoFileSource::open(
    const VideoFileSourceOptions& options) {
  if ((options.width > 0) != (options.height > 0) || options.width < 0 || options.height < 0) {
    return Error{"video files: give both width and height (or neither)"};
  }
  std::unique_ptr<VideoFileSource> source(new VideoFileSource());
  source->options_ = options;
  auto left = open_video(options.left_path);
  if (!left) return left.error();
  auto right = open_video(options.right_path);
  if (!right) return right.error();
  source->left_ = std::move(*left);
  source->right_ = std::move(*right);
  const int lw = static_cast<int>(source->left_->get(cv::CAP_PROP_FRAME_WIDTH));
  const int lh = static_cast<int>(source->left_->get(cv::CAP_PROP_FRAME_HEIGHT));
  const int rw = static_cast<int>(source->right_->get(cv::CAP_PROP_FRAME_WIDTH));
  const int rh = static_cast<int>(source->right_->get(cv::CAP_PROP_FRAME_HEIGHT));
  if (options.width > 0) {
    source->width_ = options.width;
    source->height_ = options.height;
  } else {
    if (lw != rw || lh != rh) {
      return Error{"video files: left '" + options.left_path + "' is " +
                   core::to_string(core::ImageSize{lw, lh}) + " but right '" + options.right_path +
                   "' is " + core::to_string(core::ImageSize{rw, rh}) +
                   " (give a resolution to scale both)"};
    }
    source->width_ = lw;
    source->height_ = lh;
  }
  if (source->width_ <= 0 || source->height_ <= 0) {
    return Error{"video file '" + options.left_path + "': no frame size"};
  }
  const double file_fps = source->left_->get(cv::CAP_PROP_FPS);
  source->fps_ = options.fps > 0 ? options.fps : (file_fps > 0 && file_fps < 1000 ? file_fps : 30);
  source->pacer_ = std::make_unique<FramePacer>(source->fps_);
  return source;
}

Result<core::Image> VideoFileSource::read_eye(cv::VideoCapture& video, const std::string& path) {
  cv::Mat frame;
  if (!video.read(frame) || frame.empty()) {
    // The end: loop back to the first frame.
    video.set(cv::CAP_PROP_POS_FRAMES, 0);
    if (!video.read(frame) || frame.empty()) {
      return Error{"video file '" + path + "': cannot read a frame (even after rewinding)"};
    }
  }
  core::Image image = rgb_from_bgr(frame, width_, height_);
  if (image.empty()) return Error{"video file '" + path + "': frame is not 8-bit BGR or grey"};
  return image;
}

Result<StereoCapture> VideoFileSource::capture() {
  pacer_->wait();
  StereoCapture out;
  auto left = read_eye(*left_, options_.left_path);
  out.capture_ns_left = core::monotonic_ns();
  if (!left) return left.error();
  auto right = read_eye(*right_, options_.right_path);
  out.capture_ns_right = core::monotonic_ns();
  if (!right) return right.error();
  out.left = std::move(*left);
  out.right = std::move(*right);
  out.frame_number = ++frame_;
  return out;
}

}  // namespace telear::vision
