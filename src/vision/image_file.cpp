#include "telear/vision/image_file.hpp"

#include <png.h>
#include <stb_image.h>

#include <bit>
#include <cstdio>
#include <memory>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace telear::vision {
namespace {

// stb_image's pixels as a cv::Mat that owns a copy (stb's buffer is freed on return).
cv::Mat owned_mat(void* pixels, int width, int height, int channels, bool sixteen_bits) {
  const int type = CV_MAKETYPE(sixteen_bits ? CV_16U : CV_8U, channels);
  cv::Mat image = cv::Mat(height, width, type, pixels).clone();
  stbi_image_free(pixels);
  return image;
}

// stb gives RGB(A) and grey+alpha; OpenCV's programs expect BGR(A).
cv::Mat to_opencv_order(cv::Mat image) {
  cv::Mat out;
  switch (image.channels()) {
    case 2: {  // grey + alpha: the grey in B, G and R, the file's alpha kept
      std::vector<cv::Mat> planes;
      cv::split(image, planes);
      const cv::Mat bgra[4] = {planes[0], planes[0], planes[0], planes[1]};
      cv::merge(bgra, 4, out);
      return out;
    }
    case 3:
      cv::cvtColor(image, out, cv::COLOR_RGB2BGR);
      return out;
    case 4:
      cv::cvtColor(image, out, cv::COLOR_RGBA2BGRA);
      return out;
    default:
      return image;
  }
}

cv::Mat to_eight_bits(const cv::Mat& image) {
  if (image.depth() == CV_8U) return image;
  cv::Mat out;
  image.convertTo(out, CV_8U, 1.0 / 257.0);
  return out;
}

cv::Mat converted(const cv::Mat& bgr, ImageFileMode mode) {
  if (mode == ImageFileMode::kUnchanged) return bgr;
  const cv::Mat eight = to_eight_bits(bgr);
  cv::Mat out;
  switch (eight.channels()) {
    case 1:
      if (mode == ImageFileMode::kGrey) return eight;
      cv::cvtColor(eight, out, cv::COLOR_GRAY2BGR);
      return out;
    case 3:
      if (mode == ImageFileMode::kColour) return eight;
      cv::cvtColor(eight, out, cv::COLOR_BGR2GRAY);
      return out;
    default:  // 4: BGRA
      cv::cvtColor(eight, out,
                   mode == ImageFileMode::kGrey ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGRA2BGR);
      return out;
  }
}

struct FileCloser {
  void operator()(std::FILE* f) const {
    if (f != nullptr) std::fclose(f);
  }
};

// libpng reports errors through longjmp; the message is kept for the caller.
struct PngWriteState {
  std::string error;
};

void png_error_handler(png_structp png, png_const_charp message) {
  auto* state = static_cast<PngWriteState*>(png_get_error_ptr(png));
  state->error = message;
  png_longjmp(png, 1);
}

void png_warning_handler(png_structp, png_const_charp) {}

}  // namespace

Result<cv::Mat> read_image_file(const std::string& path, ImageFileMode mode) {
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  if (!file) return Error{"cannot read image '" + path + "': cannot open the file"};
  int width = 0, height = 0, channels = 0;
  const bool sixteen_bits = stbi_is_16_bit_from_file(file.get()) != 0;
  void* pixels =
      sixteen_bits
          ? static_cast<void*>(stbi_load_from_file_16(file.get(), &width, &height, &channels, 0))
          : static_cast<void*>(stbi_load_from_file(file.get(), &width, &height, &channels, 0));
  if (pixels == nullptr) {
    const char* reason = stbi_failure_reason();
    return Error{"cannot read image '" + path +
                 "': " + (reason != nullptr ? reason : "not an image file")};
  }
  return converted(to_opencv_order(owned_mat(pixels, width, height, channels, sixteen_bits)), mode);
}

Status write_png_file(const std::string& path, const cv::Mat& image) {
  if (image.empty() || image.dims != 2) {
    return Error{"cannot write PNG file '" + path + "': empty image"};
  }
  if ((image.depth() != CV_8U && image.depth() != CV_16U) ||
      (image.channels() != 1 && image.channels() != 3 && image.channels() != 4)) {
    return Error{"cannot write PNG file '" + path +
                 "': a PNG holds 8- or 16-bit images of 1, 3 or 4 channels"};
  }
  cv::Mat rows;  // RGB(A) order, continuous
  if (image.channels() == 3) {
    cv::cvtColor(image, rows, cv::COLOR_BGR2RGB);
  } else if (image.channels() == 4) {
    cv::cvtColor(image, rows, cv::COLOR_BGRA2RGBA);
  } else {
    rows = image.isContinuous() ? image : image.clone();
  }
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "wb"));
  if (!file) return Error{"cannot write PNG file '" + path + "': cannot create the file"};

  PngWriteState state;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &state, png_error_handler,
                                            png_warning_handler);
  if (png == nullptr) return Error{"cannot write PNG file '" + path + "': libpng cannot start"};
  png_infop info = png_create_info_struct(png);
  std::vector<png_bytep> row_pointers(static_cast<size_t>(rows.rows));
  for (int y = 0; y < rows.rows; ++y) row_pointers[static_cast<size_t>(y)] = rows.ptr(y);
  if (info == nullptr || setjmp(png_jmpbuf(png)) != 0) {
    png_destroy_write_struct(&png, &info);
    return Error{"cannot write PNG file '" + path +
                 "': " + (state.error.empty() ? std::string("libpng failed") : state.error)};
  }
  png_init_io(png, file.get());
  // OpenCV's writer's defaults for speed: camera images barely compress at higher levels.
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
  png_set_compression_level(png, 1);
  png_set_compression_strategy(png, 3 /* Z_RLE */);
  const int colour_type = rows.channels() == 1   ? PNG_COLOR_TYPE_GRAY
                          : rows.channels() == 3 ? PNG_COLOR_TYPE_RGB
                                                 : PNG_COLOR_TYPE_RGBA;
  png_set_IHDR(png, info, static_cast<png_uint_32>(rows.cols), static_cast<png_uint_32>(rows.rows),
               rows.depth() == CV_16U ? 16 : 8, colour_type, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  if (rows.depth() == CV_16U && std::endian::native == std::endian::little) {
    png_set_swap(png);  // PNG stores 16-bit samples big-endian
  }
  png_write_image(png, row_pointers.data());
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  if (std::fflush(file.get()) != 0 || std::ferror(file.get()) != 0) {
    return Error{"cannot write PNG file '" + path + "': the disk refused the data"};
  }
  return Status::Ok();
}

}  // namespace telear::vision
