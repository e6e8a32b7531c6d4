#pragma once
// Both eyes of a stereo pair decoded at once: the right eye on a worker thread of its own (a
// TurboJPEG handle each) while the calling thread decodes the left. A pair's decode then takes
// about one eye's time where a core is free (at 1280x720 a pair decoded in turn was most of the
// stream's capture -> decoded latency, docs/benchmarks.md). The worker lives as long as the
// decoder: no thread is started per frame.

#include <memory>
#include <string_view>
#include <utility>

#include "telear/core/image.hpp"
#include "telear/core/result.hpp"
#include "telear/core/ycbcr_image.hpp"

namespace telear::net {

// RGB8 images, or (decode_planes) the JPEGs' Y'CbCr planes with the RGB images empty.
struct DecodedPair {
  core::Image left, right;
  core::YCbCrImage left_planes, right_planes;
};

class StereoJpegDecoder {
 public:
  StereoJpegDecoder();
  ~StereoJpegDecoder();  // stops and joins the worker
  StereoJpegDecoder(const StereoJpegDecoder&) = delete;
  StereoJpegDecoder& operator=(const StereoJpegDecoder&) = delete;

  // Decodes both; the first eye's error if both fail (named "left eye: ..."/"right eye: ...").
  // Not reentrant: one caller at a time (the vision client's decode thread).
  Result<DecodedPair> decode(std::string_view left_jpeg, std::string_view right_jpeg);
  // The same to Y'CbCr planes (JpegDecoder::decode_planes): no colour conversion.
  Result<DecodedPair> decode_planes(std::string_view left_jpeg, std::string_view right_jpeg);

 private:
  Result<DecodedPair> decode_pair(std::string_view left_jpeg, std::string_view right_jpeg,
                                  bool planes);
  struct Worker;
  std::unique_ptr<Worker> worker_;
};

}  // namespace telear::net
