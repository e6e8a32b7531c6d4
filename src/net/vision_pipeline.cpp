#include "telear/net/vision_pipeline.hpp"

#include <spdlog/spdlog.h>

#include <cmath>

#include "telear/core/image_size.hpp"
#include "telear/vision/opencv_frame.hpp"

namespace telear::net {

Status validate_stream_settings(const StreamSettings& s) {
  if (!std::isfinite(s.max_rate_hz) || s.max_rate_hz < 0.0) {
    return Error{"max_rate_hz " + std::to_string(s.max_rate_hz) +
                 " must be 0 (as fast as the source) or positive"};
  }
  if (s.jpeg_quality < 0 || s.jpeg_quality > 100) {
    return Error{"jpeg_quality " + std::to_string(s.jpeg_quality) +
                 " must be 1..100 (0: the server's default)"};
  }
  if ((s.width == 0) != (s.height == 0)) {
    return Error{"width and height must both be 0 (the source's size) or both be given"};
  }
  if (s.width < 0 || s.height < 0 || s.width > 8192 || s.height > 8192 ||
      (s.width != 0 && (s.width < 16 || s.height < 16))) {
    return Error{"size " + core::to_string(core::ImageSize{s.width, s.height}) +
                 " is outside 16x16 .. 8192x8192"};
  }
  return {};
}

Result<EncodedStereo> encode_stereo(JpegEncoder& encoder, const vision::StereoCapture& capture,
                                    int width, int height, int quality) {
  EncodedStereo out;
  out.frame_id = capture.frame_number;
  out.capture_ns_left = capture.capture_ns_left;
  out.capture_ns_right = capture.capture_ns_right;
  out.scene = capture.scene;
  out.quality = quality;
  out.encode_start_ns = core::monotonic_ns();
  const bool scale =
      width > 0 && height > 0 && (width != capture.left.width || height != capture.left.height);
  auto left = scale ? encoder.encode(vision::resize_rgb(capture.left, width, height), quality)
                    : encoder.encode(capture.left, quality);
  if (!left) return Error{"left eye: " + left.error().message};
  auto right = scale ? encoder.encode(vision::resize_rgb(capture.right, width, height), quality)
                     : encoder.encode(capture.right, quality);
  if (!right) return Error{"right eye: " + right.error().message};
  out.encode_end_ns = core::monotonic_ns();
  out.left_jpeg = std::move(*left);
  out.right_jpeg = std::move(*right);
  out.width = scale ? width : capture.left.width;
  out.height = scale ? height : capture.left.height;
  return out;
}

// [SECTION] pipeline

VisionPipeline::VisionPipeline(std::unique_ptr<vision::StereoSource> source,
                               VisionPipelineOptions options)
    : source_(std::move(source)), options_(options) {
  assert(source_ != nullptr && "VisionPipeline: no source");
  assert(options_.default_quality >= 1 && options_.default_quality <= 100 &&
         "VisionPipeline: default quality outside 1..100");
}

VisionPipeline::~VisionPipeline() {
  stop();
}

Status VisionPipeline::start() {
  assert(!capture_thread_.joinable() && "VisionPipeline::start(): already started");
  std::promise<Status> prepared;
  auto prepared_future = prepared.get_future();
  capture_thread_ = std::thread([this, &prepared] { capture_loop(&prepared); });
  Status status = prepared_future.get();
  if (!status) {
    capture_thread_.join();
    return status;
  }
  encode_thread_ = std::thread([this] { encode_loop(); });
  return {};
}

void VisionPipeline::stop() {
  stopping_ = true;
  captured_.close();
  encoded_.close();
  if (capture_thread_.joinable()) capture_thread_.join();
  if (encode_thread_.joinable()) encode_thread_.join();
}

PipelineStats VisionPipeline::stats() const {
  PipelineStats s;
  s.captured = captured_count_;
  s.encoded = encoded_count_;
  s.capture_errors = capture_errors_;
  s.encode_errors = encode_errors_;
  std::lock_guard lock(error_mutex_);
  s.last_error = last_error_;
  return s;
}

void VisionPipeline::record_error(const std::string& message, bool capture) {
  (capture ? capture_errors_ : encode_errors_)++;
  std::lock_guard lock(error_mutex_);
  // A failing camera fails every retry: log a message when it changes, not every time.
  if (message != last_error_) spdlog::error("vision pipeline: {}", message);
  last_error_ = message;
}

void VisionPipeline::capture_loop(std::promise<Status>* prepared) {
  Status status = source_->prepare();
  const bool ok = status.ok();
  prepared->set_value(std::move(status));  // `prepared` dies once start() has the value
  if (!ok) return;
  while (!stopping_) {
    auto capture = source_->capture();
    if (!capture) {
      record_error(source_->name() + " source: " + capture.error().message, true);
      // Retry after a pause (a camera that was unplugged may come back), in short steps so
      // stop() is not held up.
      for (double waited = 0; waited < options_.capture_retry_s && !stopping_; waited += 0.01) {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      }
      continue;
    }
    ++captured_count_;
    captured_.put(std::move(*capture));
  }
  source_->release();
}

void VisionPipeline::encode_loop() {
  JpegEncoder encoder;
  std::uint64_t last = 0;
  while (!stopping_) {
    auto taken = captured_.wait_take(last, std::chrono::milliseconds(100));
    if (!taken) continue;  // timeout, or closed (stopping_ is then set)
    last = taken->number;
    auto encoded = encode_stereo(encoder, *taken->item, 0, 0, options_.default_quality);
    if (!encoded) {
      record_error("encode: " + encoded.error().message, false);
      continue;
    }
    ++encoded_count_;
    encoded_.put(std::move(*encoded));
  }
}

Result<FrameSubscriber> VisionPipeline::subscribe(const StreamSettings& settings) const {
  if (auto valid = validate_stream_settings(settings); !valid) return valid.error();
  const int quality = settings.jpeg_quality == 0 ? options_.default_quality : settings.jpeg_quality;
  const bool native_size = settings.width == 0 || (settings.width == source_->width() &&
                                                   settings.height == source_->height());
  const bool custom = quality != options_.default_quality || !native_size;
  return FrameSubscriber(*this, settings, custom);
}

// [SECTION] subscriber

FrameSubscriber::FrameSubscriber(const VisionPipeline& pipeline, const StreamSettings& settings,
                                 bool custom)
    : pipeline_(&pipeline), settings_(settings), custom_(custom) {
  if (settings_.jpeg_quality == 0) settings_.jpeg_quality = pipeline.options().default_quality;
  if (custom_) encoder_ = std::make_unique<JpegEncoder>();
}

bool FrameSubscriber::closed() const {
  return custom_ ? pipeline_->captured().closed() : pipeline_->encoded().closed();
}

std::optional<FrameSubscriber::Delivery> FrameSubscriber::next(std::chrono::nanoseconds timeout) {
  const std::int64_t deadline = core::monotonic_ns() + timeout.count();
  // The rate limit: wait out the rest of the period, in short steps to notice a shutdown.
  if (settings_.max_rate_hz > 0.0 && last_delivery_ns_ != 0) {
    const std::int64_t due = last_delivery_ns_ + core::s_to_ns(1.0 / settings_.max_rate_hz);
    for (std::int64_t now = core::monotonic_ns(); now < due; now = core::monotonic_ns()) {
      if (closed() || now >= deadline) return std::nullopt;
      std::this_thread::sleep_for(std::chrono::nanoseconds(
          std::min<std::int64_t>({due - now, deadline - now, 20'000'000})));
    }
  }
  const auto remaining =
      std::chrono::nanoseconds(std::max<std::int64_t>(0, deadline - core::monotonic_ns()));
  std::shared_ptr<const EncodedStereo> frame;
  if (custom_) {
    auto taken = pipeline_->captured().wait_take(last_number_, remaining);
    if (!taken) return std::nullopt;
    last_number_ = taken->number;
    auto encoded = encode_stereo(*encoder_, *taken->item, settings_.width, settings_.height,
                                 settings_.jpeg_quality);
    if (!encoded) {
      error_ = encoded.error().message;
      return std::nullopt;
    }
    frame = std::make_shared<const EncodedStereo>(std::move(*encoded));
  } else {
    auto taken = pipeline_->encoded().wait_take(last_number_, remaining);
    if (!taken) return std::nullopt;
    last_number_ = taken->number;
    frame = taken->item;
  }
  Delivery delivery;
  delivery.frames_skipped = last_frame_id_ == 0 || frame->frame_id <= last_frame_id_
                                ? 0
                                : frame->frame_id - last_frame_id_ - 1;
  last_frame_id_ = frame->frame_id;
  last_delivery_ns_ = core::monotonic_ns();
  delivery.frame = std::move(frame);
  return delivery;
}

}  // namespace telear::net
