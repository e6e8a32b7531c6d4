#include "mp4_writer.hpp"

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "telear/core/number_format.hpp"

namespace telear::vision {
namespace {

class OpenCvMp4Writer final : public VideoWriter {
 public:
  OpenCvMp4Writer(std::unique_ptr<cv::VideoWriter> writer, VideoWriterOptions options,
                  std::string codec, std::string warning)
      : writer_(std::move(writer)),
        options_(std::move(options)),
        codec_(std::move(codec)),
        warning_(std::move(warning)) {}
  ~OpenCvMp4Writer() override { close(); }

  Status write(const core::Image& rgb) override {
    if (!writer_->isOpened()) return Error{"the video " + options_.path + " is closed"};
    if (rgb.width != options_.width || rgb.height != options_.height || rgb.channels != 3 ||
        rgb.pixels.size() != static_cast<std::size_t>(rgb.width) * rgb.height * 3) {
      return Error{"the video " + options_.path + " takes " + std::to_string(options_.width) + "x" +
                   std::to_string(options_.height) + " RGB frames, not " +
                   std::to_string(rgb.width) + "x" + std::to_string(rgb.height) + " with " +
                   std::to_string(rgb.channels) + " channels"};
    }
    // OpenCV's writer takes BGR.
    const cv::Mat frame(rgb.height, rgb.width, CV_8UC3,
                        const_cast<std::uint8_t*>(rgb.pixels.data()));
    cv::cvtColor(frame, bgr_, cv::COLOR_RGB2BGR);
    writer_->write(bgr_);
    return Status::Ok();
  }
  std::string codec() const override { return codec_; }
  std::string warning() const override { return warning_; }
  void close() override { writer_->release(); }

 private:
  std::unique_ptr<cv::VideoWriter> writer_;
  VideoWriterOptions options_;
  std::string codec_, warning_;
  cv::Mat bgr_;
};

}  // namespace

Result<std::unique_ptr<VideoWriter>> open_opencv_mp4_writer(const VideoWriterOptions& options) {
  if (options.width <= 0 || options.height <= 0 || !(options.fps > 0.0) ||
      !std::isfinite(options.fps)) {
    return Error{"the video " + options.path + ": size " + std::to_string(options.width) + "x" +
                 std::to_string(options.height) + " and rate " + core::format_number(options.fps) +
                 " fps must be positive"};
  }
  auto writer = std::make_unique<cv::VideoWriter>();
  const cv::Size size(options.width, options.height);
  writer->open(options.path, cv::CAP_FFMPEG, cv::VideoWriter::fourcc('a', 'v', 'c', '1'),
               options.fps, size);
  if (writer->isOpened()) {
    return std::unique_ptr<VideoWriter>(
        std::make_unique<OpenCvMp4Writer>(std::move(writer), options, "avc1", ""));
  }
  writer->open(options.path, cv::VideoWriter::fourcc('m', 'p', '4', 'v'), options.fps, size);
  if (!writer->isOpened()) {
    return Error{"cannot write the video " + options.path +
                 ": neither an H.264 (avc1) nor an MPEG-4 (mp4v) writer opens; check the "
                 "folder and OpenCV's FFmpeg support, or record without video"};
  }
  return std::unique_ptr<VideoWriter>(std::make_unique<OpenCvMp4Writer>(
      std::move(writer), options, "mp4v",
      "this OpenCV cannot write H.264 (avc1); " + options.path +
          " is MPEG-4 part 2 (mp4v), which browsers may not play"));
}

}  // namespace telear::vision
