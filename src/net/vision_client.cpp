#include "telear/net/vision_client.hpp"

#include <grpcpp/grpcpp.h>

#include <algorithm>
#include <atomic>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>

#include "telear/core/clock.hpp"
#include "telear/net/client_base.hpp"
#include "telear/net/jpeg_codec.hpp"
#include "telear/net/latest_slot.hpp"
#include "telear/net/stereo_jpeg_decoder.hpp"
#include "telear/net/vision_messages.hpp"
#include "telear/v1/vision.grpc.pb.h"

namespace telear::net {
namespace {

double seconds_between(std::int64_t from_ns, std::int64_t to_ns) {
  return core::ns_to_s(to_ns - from_ns);
}

}  // namespace

// Stereo 1280x720 JPEG pairs are a few hundred KB; leave room for large frames.
constexpr int kMaxReceiveBytes = 64 * 1024 * 1024;

struct VisionClient::Impl {
  // One message as it came off the wire, stamped on arrival. A member type, not a file-local
  // one: a field of Impl (which has linkage) of file-local type is what GCC warns about
  // (-Wsubobject-linkage) once this file is compiled as part of a unity batch.
  struct Received {
    telear::v1::StereoFrame message;
    std::int64_t receive_ns = 0;
    std::size_t bytes = 0;
  };

  explicit Impl(VisionClientOptions o)
      : options(std::move(o)),
        base(options, "vision server", kMaxReceiveBytes),
        stub(telear::v1::VisionService::NewStub(base.channel())) {}

  VisionClientOptions options;
  ClientBase base;  // channel, metadata, reconnect back-off and accounting
  std::unique_ptr<telear::v1::VisionService::Stub> stub;

  LatestSlot<Received> received;
  LatestSlot<DecodedStereoFrame> decoded;
  std::mutex threads_mutex;  // start() against stop()
  std::thread receive_thread, decode_thread, ping_thread;

  mutable std::mutex offset_mutex;
  ClockOffsetEstimator estimator;

  std::atomic<std::uint64_t> frames_received{0}, frames_decoded{0}, bytes_received{0};
  std::int64_t to_client(std::int64_t server_ns) const {
    std::lock_guard lock(offset_mutex);
    return estimator.to_client_ns(server_ns);
  }

  void receive_loop();
  void decode_loop();
  void ping_loop();
};

// [SECTION] receive: the stream, reconnecting with back-off (ClientBase)

void VisionClient::Impl::receive_loop() {
  telear::v1::StreamFramesRequest request;
  request.set_max_rate_hz(options.max_rate_hz);
  request.set_jpeg_quality(options.jpeg_quality);
  request.set_width(options.width);
  request.set_height(options.height);
  base.run_stream([&](grpc::ClientContext& context, const std::function<void()>& on_message) {
    auto reader = stub->StreamFrames(&context, request);
    Received item;
    while (reader->Read(&item.message)) {
      item.receive_ns = core::monotonic_ns();
      item.bytes = item.message.ByteSizeLong();
      on_message();
      ++frames_received;
      bytes_received += item.bytes;
      if (options.on_received) {
        const telear::v1::StereoFrame& m = item.message;
        ReceivedStereoFrame frame;
        frame.frame_id = m.frame_id();
        frame.jpeg_left = &m.left().jpeg();
        frame.jpeg_right = &m.right().jpeg();
        frame.width_left = m.left().width();
        frame.height_left = m.left().height();
        frame.width_right = m.right().width();
        frame.height_right = m.right().height();
        frame.capture_ns_left = to_client(m.left().capture_ns());
        frame.capture_ns_right = to_client(m.right().capture_ns());
        frame.receive_ns = item.receive_ns;
        options.on_received(frame);
      }
      received.put(std::move(item));
      item = Received{};
    }
    return reader->Finish();
  });
}

core::Image rgb_of(const DecodedStereoFrame& frame, bool left) {
  const core::Image& rgb = left ? frame.left : frame.right;
  if (!rgb.empty()) return rgb;
  return core::to_rgb(left ? frame.left_planes : frame.right_planes);
}

// [SECTION] decode: the newest received message, both eyes, latencies

void VisionClient::Impl::decode_loop() {
  std::optional<StereoJpegDecoder> pair_decoder;  // both eyes at once
  if (options.decode_eyes_in_parallel) pair_decoder.emplace();
  JpegDecoder decoder;  // else one after the other
  const FrameDecoders decoders{pair_decoder ? &*pair_decoder : nullptr, &decoder};
  std::uint64_t last = 0;
  while (true) {
    auto taken = received.wait_take(last, std::chrono::milliseconds(100));
    if (!taken) {
      if (received.closed()) break;
      continue;
    }
    last = taken->number;
    const Received& in = *taken->item;
    const telear::v1::StereoFrame& m = in.message;
    auto pair = decode_stereo_frame(m, decoders, options.decode_planes);
    if (!pair) continue;  // a corrupt frame is dropped; the next one replaces it

    DecodedStereoFrame out;
    out.decoded_ns = core::monotonic_ns();
    out.frame_id = m.frame_id();
    out.left = std::move(pair->left);
    out.right = std::move(pair->right);
    out.left_planes = std::move(pair->left_planes);
    out.right_planes = std::move(pair->right_planes);
    out.capture_ns_left = to_client(m.left().capture_ns());
    out.capture_ns_right = to_client(m.right().capture_ns());
    out.frames_skipped_server = m.frames_skipped();
    out.frames_skipped_client = taken->skipped;
    out.jpeg_bytes = m.left().jpeg().size() + m.right().jpeg().size();
    out.message_bytes = in.bytes;
    // Stages on the client clock; the pair counts as captured when its later eye was.
    const std::int64_t capture = std::max(out.capture_ns_left, out.capture_ns_right);
    const std::int64_t encode_start = to_client(m.encode_start_ns());
    const std::int64_t encode_end = to_client(m.encode_end_ns());
    const std::int64_t send = to_client(m.server_send_ns());
    out.latency.capture_to_encode_s = seconds_between(capture, encode_start);
    out.latency.encode_s = seconds_between(encode_start, encode_end);
    out.latency.send_queue_s = seconds_between(encode_end, send);
    out.latency.network_s = seconds_between(send, in.receive_ns);
    out.latency.decode_s = seconds_between(in.receive_ns, out.decoded_ns);
    out.latency.total_s = seconds_between(capture, out.decoded_ns);
    out.scene_q = scene_configuration(m);
    if (out.scene_q.size() > 0) {
      out.scene_state_ns = m.scene_state_ns() != 0 ? to_client(m.scene_state_ns()) : 0;
    }
    decoded.put(std::move(out));
    ++frames_decoded;
  }
}

// [SECTION] ping: the clock offset

void VisionClient::Impl::ping_loop() {
  do {
    grpc::ClientContext context;
    base.prepare(context);
    telear::v1::PingRequest request;
    telear::v1::PingResponse reply;
    request.set_client_send_ns(core::monotonic_ns());
    if (stub->Ping(&context, request, &reply).ok()) {
      PingSample sample{request.client_send_ns(), reply.server_receive_ns(), reply.server_send_ns(),
                        core::monotonic_ns()};
      std::lock_guard lock(offset_mutex);
      estimator.add(sample);
    }
  } while (base.sleep_while_running(options.ping_period_s));
}

// [SECTION] public API

VisionClient::VisionClient(VisionClientOptions options)
    : impl_(std::make_unique<Impl>(std::move(options))) {}

VisionClient::~VisionClient() {
  stop();
}

void VisionClient::start() {
  std::lock_guard lock(impl_->threads_mutex);
  if (impl_->received.closed()) return;  // stopped for good
  if (!impl_->base.begin()) return;      // running
  impl_->receive_thread = std::thread([this] { impl_->receive_loop(); });
  impl_->decode_thread = std::thread([this] { impl_->decode_loop(); });
  if (impl_->options.ping_period_s > 0) {
    impl_->ping_thread = std::thread([this] { impl_->ping_loop(); });
  }
}

void VisionClient::stop() {
  std::lock_guard lock(impl_->threads_mutex);
  impl_->base.stop();
  impl_->received.close();
  impl_->decoded.close();
  for (std::thread* t : {&impl_->receive_thread, &impl_->decode_thread, &impl_->ping_thread}) {
    if (t->joinable()) t->join();
  }
}

bool VisionClient::connected() const {
  return impl_->base.connected();
}

ReconnectStats VisionClient::reconnect_stats() const {
  return impl_->base.reconnect_stats();
}

Result<CameraInfoReply> VisionClient::get_camera_info() {
  grpc::ClientContext context;
  impl_->base.prepare(context);
  telear::v1::CameraInfo info;
  const grpc::Status status =
      impl_->stub->GetCameraInfo(&context, telear::v1::GetCameraInfoRequest(), &info);
  if (!status.ok()) return impl_->base.error("GetCameraInfo", status);
  return camera_info_reply(info);
}

std::optional<std::shared_ptr<const DecodedStereoFrame>> VisionClient::latest_frame() const {
  auto taken = impl_->decoded.try_take(0);
  if (!taken) return std::nullopt;
  return taken->item;
}

std::optional<std::pair<std::shared_ptr<const DecodedStereoFrame>, std::uint64_t>>
VisionClient::wait_frame(std::uint64_t after, double timeout_s) const {
  auto taken = impl_->decoded.wait_take(after, std::chrono::nanoseconds(core::s_to_ns(timeout_s)));
  if (!taken) return std::nullopt;
  return std::make_pair(taken->item, taken->number);
}

std::optional<ClockOffset> VisionClient::clock_offset() const {
  std::lock_guard lock(impl_->offset_mutex);
  return impl_->estimator.estimate();
}

std::uint64_t VisionClient::frames_received() const {
  return impl_->frames_received;
}
std::uint64_t VisionClient::frames_decoded() const {
  return impl_->frames_decoded;
}
std::uint64_t VisionClient::bytes_received() const {
  return impl_->bytes_received;
}

}  // namespace telear::net
