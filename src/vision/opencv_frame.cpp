#include "telear/vision/opencv_frame.hpp"

#include <opencv2/imgproc.hpp>

namespace telear::vision {
namespace {

int interpolation(int from_width, int to_width) {
  return to_width < from_width ? cv::INTER_AREA : cv::INTER_LINEAR;
}

}  // namespace

core::Image rgb_from_bgr(const cv::Mat& frame, int width, int height) {
  if (frame.empty() || frame.depth() != CV_8U || (frame.channels() != 3 && frame.channels() != 1)) {
    return {};
  }
  cv::Mat rgb;
  cv::cvtColor(frame, rgb, frame.channels() == 3 ? cv::COLOR_BGR2RGB : cv::COLOR_GRAY2RGB);
  if (width > 0 && height > 0 && (width != rgb.cols || height != rgb.rows)) {
    cv::Mat scaled;
    cv::resize(rgb, scaled, cv::Size(width, height), 0, 0, interpolation(rgb.cols, width));
    rgb = scaled;
  }
  core::Image image(rgb.cols, rgb.rows, 3);
  cv::Mat view(image.height, image.width, CV_8UC3, image.pixels.data());
  rgb.copyTo(view);
  return image;
}

core::Image resize_rgb(const core::Image& image, int width, int height) {
  if (image.width == width && image.height == height) return image;
  core::Image out(width, height, image.channels);
  const cv::Mat from(image.height, image.width, CV_8UC(image.channels),
                     const_cast<std::uint8_t*>(image.pixels.data()));
  cv::Mat to(height, width, CV_8UC(image.channels), out.pixels.data());
  cv::resize(from, to, to.size(), 0, 0, interpolation(image.width, width));
  return out;
}

}  // namespace telear::vision
