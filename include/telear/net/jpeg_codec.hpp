#pragma once
// JPEG encoding and decoding of RGB8 images with TurboJPEG (libjpeg-turbo's SIMD codec, ~1 ms
// for 640x480 each way on one core), for the vision stream.
//
// Buffers. Input and output images are core::Image RGB8 (width x height x 3, top row
// first, no padding). Encoded data is a std::string of JPEG bytes (4:2:0 chroma subsampling,
// the usual choice for video: half the chroma data, invisible on camera images).
//
// Each codec object owns one TurboJPEG handle (RAII) and is used by one thread at a time;
// keep one per thread and reuse it (a handle holds the codec's working memory).
//
// Untrusted input. decode() takes bytes from the network: it reads the header first and
// refuses sizes beyond `max_pixels` before allocating, stops on libjpeg warnings (truncated
// or corrupt data is an error, not a grey image) and limits progressive scans (a crafted file
// cannot make decoding take forever). Every error says "JPEG ...: " and TurboJPEG's reason
// (tjGetErrorStr2).

#include <cstddef>
#include <string>
#include <string_view>

#include "telear/core/image.hpp"
#include "telear/core/result.hpp"
#include "telear/core/ycbcr_image.hpp"

namespace telear::net {

class JpegEncoder {
 public:
  JpegEncoder();
  ~JpegEncoder();
  JpegEncoder(JpegEncoder&& other) noexcept;
  JpegEncoder& operator=(JpegEncoder&& other) noexcept;
  JpegEncoder(const JpegEncoder&) = delete;
  JpegEncoder& operator=(const JpegEncoder&) = delete;

  // RGB8 image -> JPEG at quality 1..100 (outside: an error).
  Result<std::string> encode(const core::Image& rgb, int quality);

 private:
  void* handle_ = nullptr;  // tjhandle
};

class JpegDecoder {
 public:
  static constexpr std::size_t kDefaultMaxPixels = std::size_t{8192} * 8192;

  JpegDecoder();
  ~JpegDecoder();
  JpegDecoder(JpegDecoder&& other) noexcept;
  JpegDecoder& operator=(JpegDecoder&& other) noexcept;
  JpegDecoder(const JpegDecoder&) = delete;
  JpegDecoder& operator=(const JpegDecoder&) = delete;

  // JPEG bytes -> RGB8 image.
  Result<core::Image> decode(std::string_view jpeg, std::size_t max_pixels = kDefaultMaxPixels);
  // JPEG bytes -> its Y'CbCr planes, without the colour conversion and chroma upsampling (the
  // renderer does them on the GPU: core/ycbcr_image.hpp). A grey JPEG gets neutral chroma
  // planes (128) at half size. The same checks and errors as decode().
  Result<core::YCbCrImage> decode_planes(std::string_view jpeg,
                                         std::size_t max_pixels = kDefaultMaxPixels);

 private:
  struct Header {
    int width = 0, height = 0, subsampling = 0;
  };
  Result<Header> read_header(std::string_view jpeg, std::size_t max_pixels);

  void* handle_ = nullptr;  // tjhandle
};

}  // namespace telear::net
