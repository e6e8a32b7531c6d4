#pragma once
// What the vision client makes of the vision server's messages: a StereoFrame's two JPEGs
// decoded (RGB, or Y'CbCr planes), and a CameraInfo as the cameras the overlay draws through.
// The server may be anyone's, so nothing it sends is trusted: a corrupt eye is an error (the
// frame is dropped and the next replaces it), a camera that is no camera (zero size, focal
// length not positive or not finite, a lens model telear lacks) is refused with the field
// named, and the simulated rig's configuration is kept only when every value is finite. The
// fuzz harness of this door (fuzz/vision_messages_fuzz.cpp) calls these functions.

#include "telear/core/result.hpp"
#include "telear/net/jpeg_codec.hpp"
#include "telear/net/stereo_jpeg_decoder.hpp"
#include "telear/net/vision_client.hpp"
#include "telear/v1/vision.pb.h"

namespace telear::net {

// The decoders a client keeps for its stream: both eyes at once (`pair`, when set) or one
// after the other (`single`).
struct FrameDecoders {
  StereoJpegDecoder* pair = nullptr;
  JpegDecoder* single = nullptr;
};

// Both eyes of `frame`, to RGB or (planes) to Y'CbCr; errors name the eye.
Result<DecodedPair> decode_stereo_frame(const telear::v1::StereoFrame& frame,
                                        const FrameDecoders& decoders, bool planes);

// The simulated rig's configuration a frame carries, or empty (none sent, or not finite).
Eigen::VectorXd scene_configuration(const telear::v1::StereoFrame& frame);

// The reply to GetCameraInfo: the calibration file the server sends when it is a stereo file,
// else the intrinsics fields, each camera checked (vision::validate_camera).
Result<CameraInfoReply> camera_info_reply(const telear::v1::CameraInfo& info);

}  // namespace telear::net
