#pragma once
// The vision server's video pipeline: capture -> encode -> send, each stage on its own
// thread, handing the NEWEST frame to the next through a latest-wins slot
// (telear/net/latest_slot.hpp):
//
//   source.capture()           JpegEncoder (default)          per-client StreamFrames thread
//   [capture thread] --put--> captured slot --> [encode thread] --put--> encoded slot
//                                   |                                      | FrameSubscriber
//                                   +--> (custom size/quality) per-client  +--> next() --> Write
//                                        encode on the client's own thread
//
// Nothing queues: a stage that is busy when a newer frame arrives never sees the older one.
// A slow client (its Write blocks on the network) only delays its own thread; the capture and
// encode threads and every other client go on at their own pace, and the slow client's next
// frame is the newest (frames_skipped says how many source frames it missed).
//
// Per-client resolution and quality. The encode thread serves the default: the source's size
// at the server's default quality, encoded once and shared by every client asking for it.
// A client asking for another size or quality encodes on its own stream thread from the
// captured slot (scale with INTER_AREA, then TurboJPEG): the cost is paid by that client's
// thread only, so an expensive request never slows another client or the capture. (Two
// clients with the same custom request each encode; caching distinct requests is not worth
// the bookkeeping for the few viewers a robot has.)
//
// Errors of the source and the encoder are counted (stats()) and logged through spdlog, once
// per distinct message (a camera that stays unplugged is one line, not ten a second).
//
// Frame numbers. frame_id is the source's frame number (1, 2, 3 ...), so skipped frames are
// counted against the source, whichever slot a client reads: skipped = id - previous id - 1.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <future>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "telear/core/result.hpp"
#include "telear/net/jpeg_codec.hpp"
#include "telear/net/latest_slot.hpp"
#include "telear/vision/stereo_source.hpp"

namespace telear::net {

// One stereo pair as JPEG, ready to send.
struct EncodedStereo {
  std::uint64_t frame_id = 0;
  std::string left_jpeg, right_jpeg;
  int width = 0, height = 0, quality = 0;
  std::int64_t capture_ns_left = 0, capture_ns_right = 0;
  std::int64_t encode_start_ns = 0, encode_end_ns = 0;  // both eyes
  std::optional<vision::SceneState> scene;
};

// What a client asks for (StreamFramesRequest).
struct StreamSettings {
  double max_rate_hz = 0.0;   // 0: as fast as the source
  int jpeg_quality = 0;       // 1..100; 0: the server's default
  int width = 0, height = 0;  // 0: the source's size
};

// Errors name the field: "max_rate_hz -1 is negative" etc.
Status validate_stream_settings(const StreamSettings& settings);

struct VisionPipelineOptions {
  int default_quality = 85;
  double capture_retry_s = 0.1;  // pause after a failed capture before the next attempt
};

struct PipelineStats {
  std::uint64_t captured = 0, encoded = 0, capture_errors = 0, encode_errors = 0;
  std::string last_error;
};

class VisionPipeline;

// One client's view of the pipeline: which frame it may send next.
class FrameSubscriber {
 public:
  struct Delivery {
    std::shared_ptr<const EncodedStereo> frame;
    std::uint64_t frames_skipped = 0;  // source frames since this subscriber's previous one
  };

  // Waits up to `timeout` for the newest frame not yet delivered to this subscriber, no
  // sooner than 1 / max_rate_hz after the previous delivery. nullopt: timeout, or the
  // pipeline stopped (closed() then says so), or a per-client encode failed (error()).
  std::optional<Delivery> next(std::chrono::nanoseconds timeout);
  bool closed() const;
  const std::string& error() const { return error_; }
  bool custom_encode() const { return custom_; }

 private:
  friend class VisionPipeline;
  FrameSubscriber(const VisionPipeline& pipeline, const StreamSettings& settings, bool custom);

  const VisionPipeline* pipeline_;
  StreamSettings settings_;
  bool custom_ = false;
  std::uint64_t last_number_ = 0;    // slot number last taken
  std::uint64_t last_frame_id_ = 0;  // frame id last delivered
  std::int64_t last_delivery_ns_ = 0;
  std::unique_ptr<JpegEncoder> encoder_;  // custom encodes only
  std::string error_;
};

class VisionPipeline {
 public:
  explicit VisionPipeline(std::unique_ptr<vision::StereoSource> source,
                          VisionPipelineOptions options = {});
  ~VisionPipeline();  // stop()
  VisionPipeline(const VisionPipeline&) = delete;
  VisionPipeline& operator=(const VisionPipeline&) = delete;

  // Starts the capture and encode threads; returns the source's prepare() error, if any
  // (then no thread is left running).
  Status start();
  // Closes both slots (every waiting subscriber returns at once) and joins the threads.
  void stop();

  const vision::StereoSource& source() const { return *source_; }
  const VisionPipelineOptions& options() const { return options_; }
  const LatestSlot<vision::StereoCapture>& captured() const { return captured_; }
  const LatestSlot<EncodedStereo>& encoded() const { return encoded_; }
  PipelineStats stats() const;

  // A subscriber for `settings` (validated: an error names the field).
  Result<FrameSubscriber> subscribe(const StreamSettings& settings) const;

 private:
  void capture_loop(std::promise<Status>* prepared);
  void encode_loop();
  void record_error(const std::string& message, bool capture);

  std::unique_ptr<vision::StereoSource> source_;
  VisionPipelineOptions options_;
  LatestSlot<vision::StereoCapture> captured_;
  LatestSlot<EncodedStereo> encoded_;
  std::atomic<bool> stopping_{false};
  std::thread capture_thread_, encode_thread_;
  std::atomic<std::uint64_t> captured_count_{0}, encoded_count_{0}, capture_errors_{0},
      encode_errors_{0};
  mutable std::mutex error_mutex_;
  std::string last_error_;
};

// Encodes one pair at (width, height, quality) (0 size: as captured); stamps the encode times.
Result<EncodedStereo> encode_stereo(JpegEncoder& encoder, const vision::StereoCapture& capture,
                                    int width, int height, int quality);

}  // namespace telear::net
