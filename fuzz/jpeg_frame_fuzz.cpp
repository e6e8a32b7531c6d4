// Door: a stereo frame's eye from the network, decoded as the vision client decodes it
// (net::JpegDecoder::decode to RGB, decode_planes to Y'CbCr), under the client's pixel limit.

#include "fuzz_input.hpp"
#include "telear/net/jpeg_codec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace telear;
  static net::JpegDecoder decoder;
  const std::string_view jpeg(reinterpret_cast<const char*>(data), size);
  // A smaller limit than the client's 8192^2: a fuzzer's 64 MP image is no finding, only slow.
  constexpr std::size_t kMaxPixels = 4096 * 4096;
  (void)decoder.decode(jpeg, kMaxPixels);
  (void)decoder.decode_planes(jpeg, kMaxPixels);
  return 0;
}
