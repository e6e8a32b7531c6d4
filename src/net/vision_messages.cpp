#include "telear/net/vision_messages.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "telear/vision/camera_file.hpp"

namespace telear::net {
namespace {

// The intrinsics fields of a CameraInfo; a model name or coefficient count that does not fit
// is an error (a camera with the wrong lens model would overlay the arm in the wrong place).
Result<vision::CameraModel> model_from_intrinsics(const telear::v1::CameraIntrinsics& in,
                                                  const char* eye) {
  vision::CameraModel camera;
  camera.width = in.width();
  camera.height = in.height();
  if (in.fc_size() == 2) {
    camera.fx = in.fc(0);
    camera.fy = in.fc(1);
  }
  if (in.cc_size() == 2) {
    camera.cx = in.cc(0);
    camera.cy = in.cc(1);
  }
  camera.alpha_c = in.alpha_c();
  auto distortion = [&in]() -> Result<vision::Distortion> {
    auto model = vision::parse_distortion_model(
        in.distortion_model().empty() ? "plumb_bob" : in.distortion_model());
    if (!model) return model.error();
    return vision::Distortion::from_coefficients(
        *model, std::vector<double>(in.kc().begin(), in.kc().end()));
  }();
  if (!distortion) {
    return Error{std::string("vision server camera info, ") + eye + ": " +
                 distortion.error().message};
  }
  camera.kc = *distortion;
  if (Status valid = vision::validate_camera(camera); !valid) {
    return Error{std::string("vision server camera info, ") + eye + ": " + valid.error().message};
  }
  return camera;
}

}  // namespace

Result<DecodedPair> decode_stereo_frame(const telear::v1::StereoFrame& frame,
                                        const FrameDecoders& decoders, bool planes) {
  if (decoders.pair != nullptr) {
    return planes ? decoders.pair->decode_planes(frame.left().jpeg(), frame.right().jpeg())
                  : decoders.pair->decode(frame.left().jpeg(), frame.right().jpeg());
  }
  JpegDecoder& decoder = *decoders.single;
  DecodedPair pair;
  if (planes) {
    auto left = decoder.decode_planes(frame.left().jpeg());
    if (!left) return Error{"left eye: " + left.error().message};
    auto right = decoder.decode_planes(frame.right().jpeg());
    if (!right) return Error{"right eye: " + right.error().message};
    pair.left_planes = std::move(*left);
    pair.right_planes = std::move(*right);
    return pair;
  }
  auto left = decoder.decode(frame.left().jpeg());
  if (!left) return Error{"left eye: " + left.error().message};
  auto right = decoder.decode(frame.right().jpeg());
  if (!right) return Error{"right eye: " + right.error().message};
  pair.left = std::move(*left);
  pair.right = std::move(*right);
  return pair;
}

Eigen::VectorXd scene_configuration(const telear::v1::StereoFrame& frame) {
  if (frame.scene_q_size() == 0) return {};
  Eigen::VectorXd q =
      Eigen::Map<const Eigen::VectorXd>(frame.scene_q().data(), frame.scene_q_size());
  if (!q.allFinite()) return {};
  return q;
}

Result<CameraInfoReply> camera_info_reply(const telear::v1::CameraInfo& info) {
  CameraInfoReply reply;
  reply.found = info.found();
  reply.source = info.source();
  reply.source_width = info.source_width();
  reply.source_height = info.source_height();
  reply.source_fps = info.source_fps();
  if (!reply.found) return reply;
  reply.calibration_yaml = info.calibration_yaml();
  // The file itself carries everything (poses included); the fields are the fallback.
  auto file = vision::parse_camera_yaml(info.calibration_yaml(), "vision server calibration");
  if (file && file->is_stereo()) {
    reply.cameras.left = file->left;
    reply.cameras.right = *file->right;
    return reply;
  }
  auto left = model_from_intrinsics(info.left(), "left");
  if (!left) return left.error();
  auto right = model_from_intrinsics(info.right(), "right");
  if (!right) return right.error();
  reply.cameras.left = *left;
  reply.cameras.right = *right;
  return reply;
}

}  // namespace telear::net
