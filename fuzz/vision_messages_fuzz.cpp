// Door: the vision server's messages as the vision client reads them -- any server the operator
// connects to may send anything. The first byte picks the message; the rest is its protobuf
// bytes: a StereoFrame (both eyes decoded as the client decodes them, to RGB and to Y'CbCr
// planes, one eye after the other and both at once, and the simulated rig's configuration it
// carries) or a CameraInfo (net::camera_info_reply: the calibration file, else the intrinsics
// fields, checked).

#include <google/protobuf/stubs/logging.h>

#include "fuzz_input.hpp"
#include "telear/net/vision_messages.hpp"

// protobuf logs every string field that is not UTF-8 as it refuses the message: no finding,
// and at thousands of inputs a second most of the output.
const bool kProtobufQuiet = [] {
  google::protobuf::SetLogHandler(nullptr);
  return true;
}();

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace telear;
  const std::size_t door = fuzz::pick(data, size, 2);
  if (door == 0) {
    telear::v1::StereoFrame frame;
    if (!frame.ParseFromArray(data, static_cast<int>(size))) return 0;
    static net::JpegDecoder single;
    static net::StereoJpegDecoder pair;
    for (const bool planes : {false, true}) {
      (void)net::decode_stereo_frame(frame, {nullptr, &single}, planes);
      (void)net::decode_stereo_frame(frame, {&pair, &single}, planes);
    }
    (void)net::scene_configuration(frame);
  } else {
    telear::v1::CameraInfo info;
    if (!info.ParseFromArray(data, static_cast<int>(size))) return 0;
    (void)net::camera_info_reply(info);
  }
  return 0;
}
