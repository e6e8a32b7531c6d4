#pragma once
// VisionService (proto/telear/v1/vision.proto) over a VisionPipeline: GetCameraInfo,
// StreamFrames, Ping. gRPC's synchronous server runs each StreamFrames call on its own
// thread: that thread is the client's send stage (telear/net/vision_pipeline.hpp): it takes the
// newest frame for its client from a FrameSubscriber, fills a StereoFrame and Write()s it;
// while Write() blocks on a slow network only this client waits.
//
// Authentication: with a BearerAuth (telear/net/bearer_auth.hpp) every call needs
// `authorization: Bearer <token>` (vision is read access; observers are allowed only when the
// BearerAuth says so). Without one, the service is open.
//
// Log (spdlog, telear/net/server_log.hpp): info when a stream opens and closes (the caller's
// name and peer, telear/net/client_name.hpp; frames sent and skipped), debug for each
// delivery that skipped source frames, warn for a refused call, error for a failed stream.
//
// Shutdown: begin_shutdown() makes every StreamFrames loop return within ~0.1 s (each waits
// on the pipeline with a short timeout and checks the flag and its call's cancellation).

#include <atomic>
#include <optional>
#include <string>

#include "telear/net/bearer_auth.hpp"
#include "telear/net/vision_pipeline.hpp"
#include "telear/v1/vision.grpc.pb.h"
#include "telear/vision/camera_file.hpp"

namespace telear::net {

struct VisionServiceConfig {
  std::optional<BearerAuth> auth;                 // nullopt: no token needed
  std::optional<vision::CameraFile> calibration;  // a stereo camera file, for GetCameraInfo
  std::string calibration_yaml;                   // its text, as loaded
  int max_streams = 16;                           // concurrent StreamFrames calls
};

// CameraInfo of a stereo calibration (R, t of the right camera in the left camera's frame
// from the two T_cam_base: T_right_left = T_right_base * T_left_base^-1).
telear::v1::CameraInfo camera_info_message(const VisionServiceConfig& config,
                                           const vision::StereoSource& source);

class VisionServiceImpl final : public telear::v1::VisionService::Service {
 public:
  VisionServiceImpl(const VisionPipeline& pipeline, VisionServiceConfig config);

  grpc::Status GetCameraInfo(grpc::ServerContext* context,
                             const telear::v1::GetCameraInfoRequest* request,
                             telear::v1::CameraInfo* reply) override;
  grpc::Status StreamFrames(grpc::ServerContext* context,
                            const telear::v1::StreamFramesRequest* request,
                            grpc::ServerWriter<telear::v1::StereoFrame>* writer) override;
  grpc::Status Ping(grpc::ServerContext* context, const telear::v1::PingRequest* request,
                    telear::v1::PingResponse* reply) override;

  void begin_shutdown() { stopping_ = true; }
  int active_streams() const { return active_streams_; }

 private:
  grpc::Status authorize(const grpc::ServerContext& context, const char* what) const;

  const VisionPipeline& pipeline_;
  VisionServiceConfig config_;
  telear::v1::CameraInfo camera_info_;
  std::atomic<bool> stopping_{false};
  std::atomic<int> active_streams_{0};
};

}  // namespace telear::net
