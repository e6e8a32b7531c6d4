#pragma once
// VisionClient: receives the stereo stream of VisionService (proto/telear/v1/vision.proto)
// and decodes it, never queueing stale frames.
//
// Threads. The receive thread reads StereoFrame messages and puts each into a latest-wins
// slot; the decode thread takes the newest undecoded message, decodes both JPEGs with
// TurboJPEG into RGB images and publishes a DecodedStereoFrame into a second latest-wins slot
// that latest_frame() / wait_frame() read. A slow reader skips frames; frames that were
// received but never decoded (the decoder was busy) are counted. The receive thread
// reconnects with exponential back-off when the stream breaks (telear/net/client_base.hpp,
// which also sends the token and the client name with every call); a ping thread estimates the
// server's clock offset (telear/net/clock_offset.hpp) so per-stage latencies are meaningful across
// machines.
//
// Latency of every stage, per frame, in seconds (client clock after offset conversion): the
// six stages of telear/net/latency_stages.hpp (capture -> encode, encode, send queue, network,
// decode, capture -> decoded), in DecodedStereoFrame::latency.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "telear/core/image.hpp"
#include "telear/core/result.hpp"
#include "telear/core/ycbcr_image.hpp"
#include "telear/net/client_options.hpp"
#include "telear/net/clock_offset.hpp"
#include "telear/net/latency_stages.hpp"
#include "telear/net/reconnect.hpp"
#include "telear/vision/camera_model.hpp"

namespace telear::net {

// One stereo frame as it arrived, before decoding: each eye's JPEG exactly as the server sent
// it (a recorder keeps these bytes, not re-encoded pixels).
struct ReceivedStereoFrame {
  std::uint64_t frame_id = 0;
  const std::string* jpeg_left = nullptr;  // valid during the callback only
  const std::string* jpeg_right = nullptr;
  int width_left = 0, height_left = 0, width_right = 0, height_right = 0;
  std::int64_t capture_ns_left = 0;  // client clock (converted)
  std::int64_t capture_ns_right = 0;
  std::int64_t receive_ns = 0;  // client clock
};

struct VisionClientOptions : ClientOptions {
  double max_rate_hz = 0.0;   // 0: as fast as the source
  int jpeg_quality = 0;       // 0: the server's default
  int width = 0, height = 0;  // 0: the source's size
  double ping_period_s = 1.0;
  // Both eyes decoded at once (net/stereo_jpeg_decoder.hpp: the right eye on a worker thread);
  // false: one after the other on the decode thread (a single-core machine; the benchmark's
  // comparison).
  bool decode_eyes_in_parallel = true;
  // Decode to the JPEGs' Y'CbCr planes (DecodedStereoFrame::left_planes, right_planes; left and
  // right then empty): no CPU colour conversion, for a renderer that converts on the GPU
  // (render::VideoBackground::upload_planes). Consumers that need RGB call rgb_of().
  bool decode_planes = false;
  // Called on the receive thread for every frame received, before it may be skipped by the
  // decoder: keep it short (copy what you need and return); it delays the next receive.
  std::function<void(const ReceivedStereoFrame&)> on_received;
};

struct DecodedStereoFrame {
  std::uint64_t frame_id = 0;
  core::Image left, right;                     // RGB8, top row first (empty with decode_planes)
  core::YCbCrImage left_planes, right_planes;  // with decode_planes only
  std::int64_t capture_ns_left = 0;            // client clock (converted)
  std::int64_t capture_ns_right = 0;
  std::int64_t decoded_ns = 0;              // client clock
  std::uint64_t frames_skipped_server = 0;  // the server skipped for this client before sending
  std::uint64_t frames_skipped_client = 0;  // received here but replaced before decoding
  std::size_t jpeg_bytes = 0;               // both eyes
  std::size_t message_bytes = 0;            // the whole StereoFrame message
  StageLatency latency;
  Eigen::VectorXd scene_q;          // the simulated rig's configuration, when sent
  std::int64_t scene_state_ns = 0;  // client clock
};

// An eye of a decoded frame as RGB8: the decoded image, or its planes converted on the CPU
// (core::to_rgb) when the client decoded to planes. For the few consumers that need RGB (a
// registration capture); the view uploads the planes as they are.
core::Image rgb_of(const DecodedStereoFrame& frame, bool left);

struct CameraInfoReply {
  bool found = false;
  vision::StereoCameraModel cameras;  // valid when found
  std::string calibration_yaml;       // the server's calibration file as it is (when found)
  std::string source;
  int source_width = 0, source_height = 0;
  double source_fps = 0;
};

class VisionClient {
 public:
  explicit VisionClient(VisionClientOptions options);
  ~VisionClient();
  VisionClient(const VisionClient&) = delete;
  VisionClient& operator=(const VisionClient&) = delete;

  void start();  // starts the receive, decode and ping threads; returns at once
  void stop();
  bool connected() const;                  // a frame arrived within the last second
  ReconnectStats reconnect_stats() const;  // the frame stream's (telear/net/client_base.hpp)

  Result<CameraInfoReply> get_camera_info();
  std::optional<std::shared_ptr<const DecodedStereoFrame>> latest_frame() const;
  // Waits up to timeout_s for a decoded frame with a frame number newer than `after` (the
  // slot's count, see LatestSlot); returns it with its slot number.
  std::optional<std::pair<std::shared_ptr<const DecodedStereoFrame>, std::uint64_t>> wait_frame(
      std::uint64_t after, double timeout_s) const;
  std::optional<ClockOffset> clock_offset() const;

  std::uint64_t frames_received() const;
  std::uint64_t frames_decoded() const;
  std::uint64_t bytes_received() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace telear::net
