#include "telear/net/vision_service.hpp"

#include <spdlog/spdlog.h>

#include "telear/core/clock.hpp"
#include "telear/net/client_name.hpp"

namespace telear::net {
namespace {

void fill_intrinsics(const vision::CameraModel& camera, telear::v1::CameraIntrinsics* out) {
  out->set_width(camera.width);
  out->set_height(camera.height);
  out->add_fc(camera.fx);
  out->add_fc(camera.fy);
  out->add_cc(camera.cx);
  out->add_cc(camera.cy);
  out->set_alpha_c(camera.alpha_c);
  out->set_distortion_model(vision::distortion_model_name(camera.kc.model));
  for (double k : camera.kc.coefficients()) out->add_kc(k);
}

void fill_eye(const std::string& jpeg, int width, int height, std::int64_t capture_ns,
              telear::v1::EyeImage* out) {
  out->set_jpeg(jpeg);
  out->set_width(width);
  out->set_height(height);
  out->set_capture_ns(capture_ns);
}

}  // namespace

telear::v1::CameraInfo camera_info_message(const VisionServiceConfig& config,
                                           const vision::StereoSource& source) {
  telear::v1::CameraInfo info;
  info.set_source(source.name());
  info.set_source_width(source.width());
  info.set_source_height(source.height());
  info.set_source_fps(source.fps());
  if (!config.calibration || !config.calibration->right) return info;
  const vision::CameraFile& file = *config.calibration;
  info.set_found(true);
  fill_intrinsics(file.left, info.mutable_left());
  fill_intrinsics(*file.right, info.mutable_right());
  info.set_calibration_yaml(config.calibration_yaml);
  // The pair's geometry, where the file has it: both poses (a registered file).
  if (file.left_has_pose && file.right_has_pose) {
    const Eigen::Isometry3d T_right_left = file.right->T_cam_base * file.left.T_cam_base.inverse();
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) info.add_rotation_right_left(T_right_left.linear()(r, c));
    }
    for (int r = 0; r < 3; ++r) info.add_translation_right_left_m(T_right_left.translation()(r));
  }
  return info;
}

VisionServiceImpl::VisionServiceImpl(const VisionPipeline& pipeline, VisionServiceConfig config)
    : pipeline_(pipeline), config_(std::move(config)) {
  camera_info_ = camera_info_message(config_, pipeline_.source());
}

grpc::Status VisionServiceImpl::authorize(const grpc::ServerContext& context,
                                          const char* what) const {
  if (!config_.auth) return grpc::Status::OK;
  grpc::Status status = config_.auth->authorize_read(context);
  if (!status.ok()) {
    spdlog::warn("vision call from {}: {}: refused: {}", describe_caller(context), what,
                 status.error_message());
  }
  return status;
}

grpc::Status VisionServiceImpl::GetCameraInfo(grpc::ServerContext* context,
                                              const telear::v1::GetCameraInfoRequest*,
                                              telear::v1::CameraInfo* reply) {
  if (auto status = authorize(*context, "GetCameraInfo"); !status.ok()) return status;
  *reply = camera_info_;
  return grpc::Status::OK;
}

grpc::Status VisionServiceImpl::Ping(grpc::ServerContext* context,
                                     const telear::v1::PingRequest* request,
                                     telear::v1::PingResponse* reply) {
  const std::int64_t received = core::monotonic_ns();
  if (auto status = authorize(*context, "Ping"); !status.ok()) return status;
  reply->set_client_send_ns(request->client_send_ns());
  reply->set_server_receive_ns(received);
  reply->set_server_send_ns(core::monotonic_ns());
  return grpc::Status::OK;
}

grpc::Status VisionServiceImpl::StreamFrames(grpc::ServerContext* context,
                                             const telear::v1::StreamFramesRequest* request,
                                             grpc::ServerWriter<telear::v1::StereoFrame>* writer) {
  if (auto status = authorize(*context, "StreamFrames"); !status.ok()) return status;
  const std::string who = describe_caller(*context);
  StreamSettings settings;
  settings.max_rate_hz = request->max_rate_hz();
  settings.jpeg_quality = request->jpeg_quality();
  settings.width = request->width();
  settings.height = request->height();
  auto subscriber = pipeline_.subscribe(settings);
  if (!subscriber) {
    spdlog::warn("vision stream to {} refused: {}", who, subscriber.error().message);
    return {grpc::StatusCode::INVALID_ARGUMENT, "StreamFrames: " + subscriber.error().message};
  }
  // Counted before the check so two racing calls cannot both take the last place.
  if (++active_streams_ > config_.max_streams) {
    --active_streams_;
    spdlog::warn("vision stream to {} refused: already {} streams (the maximum)", who,
                 config_.max_streams);
    return {grpc::StatusCode::RESOURCE_EXHAUSTED, "StreamFrames: the server already sends " +
                                                      std::to_string(config_.max_streams) +
                                                      " streams (its maximum)"};
  }
  spdlog::info("vision stream to {} opened ({})", who,
               subscriber->custom_encode() ? "own encode" : "shared encode");
  std::uint64_t sent = 0, skipped = 0;
  std::string why = "client left";
  telear::v1::StereoFrame message;
  while (true) {
    if (stopping_) {
      why = "server shutting down";
      break;
    }
    if (context->IsCancelled()) break;
    auto delivery = subscriber->next(std::chrono::milliseconds(100));
    if (!delivery) {
      if (!subscriber->error().empty()) {
        --active_streams_;
        spdlog::error("vision stream to {} failed: {}", who, subscriber->error());
        return {grpc::StatusCode::INTERNAL, "StreamFrames: " + subscriber->error()};
      }
      if (subscriber->closed()) {
        why = "server shutting down";
        break;
      }
      continue;
    }
    const EncodedStereo& frame = *delivery->frame;
    message.Clear();
    message.set_frame_id(frame.frame_id);
    fill_eye(frame.left_jpeg, frame.width, frame.height, frame.capture_ns_left,
             message.mutable_left());
    fill_eye(frame.right_jpeg, frame.width, frame.height, frame.capture_ns_right,
             message.mutable_right());
    message.set_encode_start_ns(frame.encode_start_ns);
    message.set_encode_end_ns(frame.encode_end_ns);
    message.set_frames_skipped(delivery->frames_skipped);
    if (frame.scene) {
      for (Eigen::Index i = 0; i < frame.scene->q.size(); ++i)
        message.add_scene_q(frame.scene->q[i]);
      message.set_scene_state_ns(frame.scene->state_ns);
    }
    message.set_server_send_ns(core::monotonic_ns());
    if (!writer->Write(message)) break;  // the client went away (or the server cancelled)
    ++sent;
    skipped += delivery->frames_skipped;
    if (delivery->frames_skipped > 0) {
      spdlog::debug("vision stream to {}: frame {} sent, {} source frames skipped before it", who,
                    frame.frame_id, delivery->frames_skipped);
    }
  }
  --active_streams_;
  spdlog::info("vision stream to {} closed ({}): {} frames sent, {} skipped", who, why, sent,
               skipped);
  return grpc::Status::OK;
}

}  // namespace telear::net
