#include "telear/net/jpeg_codec.hpp"

#include <turbojpeg.h>

#include <cassert>
#include <utility>

#include "telear/core/image_size.hpp"

namespace telear::net {
namespace {

std::string tj_error(void* handle) {
  return tjGetErrorStr2(static_cast<tjhandle>(handle));
}

void destroy(void*& handle) {
  if (handle != nullptr) tjDestroy(static_cast<tjhandle>(handle));
  handle = nullptr;
}

}  // namespace

// [SECTION] encoder

JpegEncoder::JpegEncoder() : handle_(tjInitCompress()) {
  // Only fails when out of memory: a programmer-level failure, not untrusted input.
  assert(handle_ != nullptr && "JpegEncoder: tjInitCompress failed");
}

JpegEncoder::~JpegEncoder() {
  destroy(handle_);
}

JpegEncoder::JpegEncoder(JpegEncoder&& other) noexcept
    : handle_(std::exchange(other.handle_, nullptr)) {}

JpegEncoder& JpegEncoder::operator=(JpegEncoder&& other) noexcept {
  if (this != &other) {
    destroy(handle_);
    handle_ = std::exchange(other.handle_, nullptr);
  }
  return *this;
}

Result<std::string> JpegEncoder::encode(const core::Image& rgb, int quality) {
  if (handle_ == nullptr) return Error{"JPEG encode: no TurboJPEG handle"};
  if (quality < 1 || quality > 100) {
    return Error{"JPEG encode: quality " + std::to_string(quality) + " is outside 1..100"};
  }
  if (rgb.channels != 3 || rgb.width <= 0 || rgb.height <= 0 ||
      rgb.pixels.size() != rgb.row_bytes() * static_cast<std::size_t>(rgb.height)) {
    return Error{"JPEG encode: expected a non-empty RGB8 image, got " +
                 core::to_string(core::ImageSize{rgb.width, rgb.height}) + "x" +
                 std::to_string(rgb.channels)};
  }
  // Encode straight into the string: tjBufSize is the worst case, so NOREALLOC is safe.
  std::string out(tjBufSize(rgb.width, rgb.height, TJSAMP_420), '\0');
  auto* buffer = reinterpret_cast<unsigned char*>(out.data());
  unsigned long size = out.size();
  if (tjCompress2(static_cast<tjhandle>(handle_), rgb.pixels.data(), rgb.width, 0, rgb.height,
                  TJPF_RGB, &buffer, &size, TJSAMP_420, quality, TJFLAG_NOREALLOC) != 0) {
    return Error{"JPEG encode: " + tj_error(handle_)};
  }
  out.resize(size);
  return out;
}

// [SECTION] decoder

JpegDecoder::JpegDecoder() : handle_(tjInitDecompress()) {
  assert(handle_ != nullptr && "JpegDecoder: tjInitDecompress failed");
}

JpegDecoder::~JpegDecoder() {
  destroy(handle_);
}

JpegDecoder::JpegDecoder(JpegDecoder&& other) noexcept
    : handle_(std::exchange(other.handle_, nullptr)) {}

JpegDecoder& JpegDecoder::operator=(JpegDecoder&& other) noexcept {
  if (this != &other) {
    destroy(handle_);
    handle_ = std::exchange(other.handle_, nullptr);
  }
  return *this;
}

Result<core::Image> JpegDecoder::decode(std::string_view jpeg, std::size_t max_pixels) {
  if (handle_ == nullptr) return Error{"JPEG decode: no TurboJPEG handle"};
  if (jpeg.empty()) return Error{"JPEG decode: no data (0 bytes)"};
  auto* data = reinterpret_cast<const unsigned char*>(jpeg.data());
  int width = 0, height = 0, subsampling = 0, colorspace = 0;
  if (tjDecompressHeader3(static_cast<tjhandle>(handle_), data, jpeg.size(), &width, &height,
                          &subsampling, &colorspace) != 0) {
    return Error{"JPEG decode: not a readable JPEG header (" + std::to_string(jpeg.size()) +
                 " bytes): " + tj_error(handle_)};
  }
  if (width <= 0 || height <= 0 ||
      static_cast<std::size_t>(width) * static_cast<std::size_t>(height) > max_pixels) {
    return Error{"JPEG decode: image size " + core::to_string(core::ImageSize{width, height}) +
                 " is beyond the limit of " + std::to_string(max_pixels) + " pixels"};
  }
  core::Image image(width, height, 3);
  if (tjDecompress2(static_cast<tjhandle>(handle_), data, jpeg.size(), image.pixels.data(), width,
                    0, height, TJPF_RGB, TJFLAG_STOPONWARNING | TJFLAG_LIMITSCANS) != 0) {
    return Error{"JPEG decode: corrupt " + core::to_string(core::ImageSize{width, height}) +
                 " image: " + tj_error(handle_)};
  }
  return image;
}

}  // namespace telear::net
