#include "telear/render/image_io.hpp"

#include <stb_image.h>

#include <cstring>
#include <opencv2/imgproc.hpp>

#include "telear/vision/image_file.hpp"

namespace telear::render {

Status write_png(const std::string& path, const core::Image& image) {
  if (image.empty() || image.width <= 0 || image.height <= 0 ||
      (image.channels != 1 && image.channels != 3 && image.channels != 4) ||
      image.pixels.size() != image.row_bytes() * static_cast<std::size_t>(image.height)) {
    return Error{"cannot write '" + path + "': not a valid 1-, 3- or 4-channel image"};
  }
  // vision's libpng writer (6x faster than stb's on camera images), which takes OpenCV's
  // channel order.
  const cv::Mat rows(image.height, image.width, CV_8UC(image.channels),
                     const_cast<std::uint8_t*>(image.pixels.data()), image.row_bytes());
  if (image.channels == 1) return vision::write_png_file(path, rows);
  cv::Mat bgr;
  cv::cvtColor(rows, bgr, image.channels == 3 ? cv::COLOR_RGB2BGR : cv::COLOR_RGBA2BGRA);
  return vision::write_png_file(path, bgr);
}

Result<core::Image> read_image(const std::string& path, int desired_channels) {
  int w = 0, h = 0, n = 0;
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &n, desired_channels);
  if (data == nullptr) {
    const char* reason = stbi_failure_reason();
    return Error{"cannot read image '" + path + "': " + (reason ? reason : "unknown reason")};
  }
  core::Image image(w, h, desired_channels > 0 ? desired_channels : n);
  std::memcpy(image.pixels.data(), data, image.pixels.size());
  stbi_image_free(data);
  return image;
}

}  // namespace telear::render
