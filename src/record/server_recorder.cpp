#include "telear/record/server_recorder.hpp"

#include <atomic>
#include <chrono>
#include <optional>
#include <thread>
#include <utility>

#include "telear/net/robot_client.hpp"
#include "telear/net/vision_client.hpp"
#include "telear/vision/camera_file.hpp"

namespace telear::record {

struct ServerRecorder::Impl {
  std::unique_ptr<net::RobotClient> robot;
  std::unique_ptr<net::VisionClient> vision;
  std::unique_ptr<SessionRecorder> recorder;
  // The vision client's receive thread reads it: set once the recorder exists, cleared
  // before it closes.
  std::atomic<SessionRecorder*> sink{nullptr};
  std::atomic<bool> stopping{false};
  std::thread thread;
  std::optional<Result<RecordingCounts>> result;
  bool own_states = false;  // stream_state: the own client's states are recorded here

  void run() {
    std::uint64_t frame_after = 0, state_after = 0;
    while (!stopping) {
      if (own_states) {
        if (auto state = robot->wait_state(state_after, 0.02)) {
          state_after = state->sequence;
          recorder->add_state(*state);
        }
      } else {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      }
      if (vision) {
        if (auto frame = vision->wait_frame(frame_after, 0.0)) {
          frame_after = frame->second;
          recorder->add_latency(*frame->first);
        }
      }
    }
  }
};

ServerRecorder::ServerRecorder(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

ServerRecorder::~ServerRecorder() {
  if (impl_) (void)stop();
}

Result<std::unique_ptr<ServerRecorder>> ServerRecorder::start(
    const ServerRecorderOptions& options) {
  if (options.robot_address.empty()) return Error{"recording: no robot server address"};
  if (!(options.state_rate_hz >= 1.0 && options.state_rate_hz <= 250.0)) {
    return Error{"recording: the state rate must be within 1..250 Hz"};
  }
  auto impl = std::make_unique<Impl>();
  net::RobotClientOptions robot_options;
  robot_options.address = options.robot_address;
  robot_options.token = options.token;
  robot_options.tls_root_certificate_file = options.tls_ca_file;
  robot_options.client_name = options.client_name;
  robot_options.state_rate_hz = options.state_rate_hz;
  impl->robot = std::make_unique<net::RobotClient>(robot_options);
  // Its state stream only when it records its own (else its info call is all it makes).
  if (options.stream_state) {
    impl->robot->start();
    impl->own_states = true;
  }
  auto info = impl->robot->get_info();
  if (!info) {
    return Error{"recording: robot server " + options.robot_address + ": " + info.error().message};
  }
  RecordedSetup setup;
  setup.robot = *info;
  if (!options.vision_address.empty()) {
    net::VisionClientOptions vision_options;
    vision_options.address = options.vision_address;
    vision_options.token = options.token;
    vision_options.tls_root_certificate_file = options.tls_ca_file;
    vision_options.client_name = options.client_name;
    vision_options.on_received = [sink = &impl->sink](const net::ReceivedStereoFrame& frame) {
      if (SessionRecorder* r = sink->load()) r->add_frame(frame);
    };
    impl->vision = std::make_unique<net::VisionClient>(vision_options);
    auto camera_info = impl->vision->get_camera_info();  // a call of its own: no stream
    if (!camera_info) {
      return Error{"recording: vision server " + options.vision_address + ": " +
                   camera_info.error().message};
    }
    if (camera_info->found) {
      setup.cameras = camera_info->cameras;
      setup.calibration_yaml = camera_info->calibration_yaml;
    }
    if (options.cameras) {
      setup.cameras = options.cameras;
      setup.calibration_yaml = vision::opencv_stereo_camera_yaml(*options.cameras);
    }
    if (!options.stream_video) impl->vision.reset();  // the caller feeds the frames
  }
  SessionRecorderOptions recorder_options = options.recorder;
  recorder_options.metadata["robot_server"] = options.robot_address;
  recorder_options.metadata["vision_server"] = options.vision_address;
  auto recorder = SessionRecorder::create(recorder_options, setup);
  if (!recorder) return recorder.error();
  impl->recorder = std::move(recorder).value();
  impl->sink = impl->recorder.get();
  if (impl->vision) impl->vision->start();
  impl->thread = std::thread([raw = impl.get()] { raw->run(); });
  return std::unique_ptr<ServerRecorder>(new ServerRecorder(std::move(impl)));
}

void ServerRecorder::add_log(LogLevel level, const std::string& text, std::int64_t client_ns) {
  impl_->recorder->add_log(level, text, client_ns);
}

void ServerRecorder::add_frame(const net::ReceivedStereoFrame& frame) {
  if (SessionRecorder* r = impl_->sink.load()) r->add_frame(frame);
}

void ServerRecorder::add_state(const net::RobotStateSample& sample) {
  if (SessionRecorder* r = impl_->sink.load()) r->add_state(sample);
}

void ServerRecorder::add_latency(const net::DecodedStereoFrame& frame,
                                 std::optional<std::int64_t> shown_ns) {
  if (SessionRecorder* r = impl_->sink.load()) r->add_latency(frame, shown_ns);
}

void ServerRecorder::add_plan_event(PlanEventKind kind, const std::string& text,
                                    const std::string& plan_id, const std::string& plan_hash,
                                    std::int64_t client_ns) {
  impl_->recorder->add_plan_event(kind, text, plan_id, plan_hash, client_ns);
}

void ServerRecorder::add_ghost(const Eigen::VectorXd& q, double gripper, std::int64_t client_ns) {
  impl_->recorder->add_ghost(q, gripper, client_ns);
}

std::int64_t ServerRecorder::wall_ns(std::int64_t client_ns) const {
  return impl_->recorder->wall_ns(client_ns);
}

Result<RecordingCounts> ServerRecorder::stop() {
  Impl& impl = *impl_;
  if (!impl.result) {
    impl.stopping = true;
    if (impl.thread.joinable()) impl.thread.join();
    if (impl.vision) impl.vision->stop();
    impl.sink = nullptr;
    impl.robot->stop();
    impl.result = impl.recorder->close();
  }
  return *impl.result;
}

}  // namespace telear::record
