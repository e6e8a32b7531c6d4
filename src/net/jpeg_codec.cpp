#include "telear/net/jpeg_codec.hpp"

#include <turbojpeg.h>
#include <algorithm>

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

Result<JpegDecoder::Header> JpegDecoder::read_header(std::string_view jpeg,
                                                     std::size_t max_pixels) {
  if (handle_ == nullptr) return Error{"JPEG decode: no TurboJPEG handle"};
  if (jpeg.empty()) return Error{"JPEG decode: no data (0 bytes)"};
  auto* data = reinterpret_cast<const unsigned char*>(jpeg.data());
  Header h;
  int colorspace = 0;
  if (tjDecompressHeader3(static_cast<tjhandle>(handle_), data, jpeg.size(), &h.width, &h.height,
                          &h.subsampling, &colorspace) != 0) {
    return Error{"JPEG decode: not a readable JPEG header (" + std::to_string(jpeg.size()) +
                 " bytes): " + tj_error(handle_)};
  }
  if (h.width <= 0 || h.height <= 0 ||
      static_cast<std::size_t>(h.width) * static_cast<std::size_t>(h.height) > max_pixels) {
    return Error{"JPEG decode: image size " + core::to_string(core::ImageSize{h.width, h.height}) +
                 " is beyond the limit of " + std::to_string(max_pixels) + " pixels"};
  }
  return h;
}

Result<core::YCbCrImage> JpegDecoder::decode_planes(std::string_view jpeg, std::size_t max_pixels) {
  auto header = read_header(jpeg, max_pixels);
  if (!header) return header.error();
  const int width = header->width, height = header->height;
  core::YCbCrImage planes;
  planes.width = width;
  planes.height = height;
  // TurboJPEG's luma plane is padded to the subsampling factor (a 161x121 4:2:0 image decodes
  // to a 162x122 plane): decoded padded, then trimmed to the image (even sizes need no copy).
  const int luma_width = tjPlaneWidth(0, width, header->subsampling);
  const int luma_height = tjPlaneHeight(0, height, header->subsampling);
  if (luma_width < width || luma_height < height) {
    return Error{"JPEG decode: unsupported chroma subsampling " +
                 std::to_string(header->subsampling)};
  }
  planes.y.resize(static_cast<std::size_t>(luma_width) * luma_height);
  const bool grey = header->subsampling == TJSAMP_GRAY;
  planes.chroma_width = grey ? (width + 1) / 2 : tjPlaneWidth(1, width, header->subsampling);
  planes.chroma_height = grey ? (height + 1) / 2 : tjPlaneHeight(1, height, header->subsampling);
  if (planes.chroma_width <= 0 || planes.chroma_height <= 0) {
    return Error{"JPEG decode: unsupported chroma subsampling " +
                 std::to_string(header->subsampling)};
  }
  const std::size_t chroma = static_cast<std::size_t>(planes.chroma_width) * planes.chroma_height;
  planes.cb.assign(chroma, 128);
  planes.cr.assign(chroma, 128);
  unsigned char* destinations[3] = {planes.y.data(), planes.cb.data(), planes.cr.data()};
  int strides[3] = {luma_width, planes.chroma_width, planes.chroma_width};  // (the API takes int*)
  auto* data = reinterpret_cast<const unsigned char*>(jpeg.data());
  if (tjDecompressToYUVPlanes(static_cast<tjhandle>(handle_), data, jpeg.size(), destinations,
                              width, strides, height,
                              TJFLAG_STOPONWARNING | TJFLAG_LIMITSCANS) != 0) {
    return Error{"JPEG decode: corrupt " + core::to_string(core::ImageSize{width, height}) +
                 " image: " + tj_error(handle_)};
  }
  if (luma_width != width) {
    for (int row = 1; row < height; ++row) {
      std::copy_n(planes.y.begin() + static_cast<std::ptrdiff_t>(row) * luma_width, width,
                  planes.y.begin() + static_cast<std::ptrdiff_t>(row) * width);
    }
  }
  planes.y.resize(static_cast<std::size_t>(width) * height);
  return planes;
}

Result<core::Image> JpegDecoder::decode(std::string_view jpeg, std::size_t max_pixels) {
  auto header = read_header(jpeg, max_pixels);
  if (!header) return header.error();
  const int width = header->width, height = header->height;
  auto* data = reinterpret_cast<const unsigned char*>(jpeg.data());
  core::Image image(width, height, 3);
  if (tjDecompress2(static_cast<tjhandle>(handle_), data, jpeg.size(), image.pixels.data(), width,
                    0, height, TJPF_RGB, TJFLAG_STOPONWARNING | TJFLAG_LIMITSCANS) != 0) {
    return Error{"JPEG decode: corrupt " + core::to_string(core::ImageSize{width, height}) +
                 " image: " + tj_error(handle_)};
  }
  return image;
}

}  // namespace telear::net
