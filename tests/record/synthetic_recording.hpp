#pragma once
// A recording with known content, written by the real SessionRecorder without servers: the
// PUMA 560's states at 50 Hz (its measured joints, a command offset from them by a known amount,
// a ghost), stereo frames at 30 fps with JPEG-sized payloads, their latency by stage, a log line
// and the lease taken (a plan event). The tests of RecordingSeries (tests/record) and of
// `telear report` (tests/report) check what they read against these numbers.

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "telear/core/clock.hpp"
#include "telear/core/result.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/record/session_recorder.hpp"

namespace telear::test {

struct SyntheticRecording {
  int states = 50;                                            // every kStatePeriodNs
  int frames = 30;                                            // stereo pairs, every kFramePeriodNs
  Eigen::VectorXd command_offset = Eigen::VectorXd::Zero(6);  // q_commanded - q, rad
  std::size_t left_bytes = 1000, right_bytes = 1500;          // each frame's "JPEG"
  std::uint64_t chunk_size = 1024 * 1024;                     // McapWriterOptions::chunk_size
  std::string log_line = "synthetic operator event";

  static constexpr std::int64_t kStatePeriodNs = 20'000'000;  // 50 Hz
  static constexpr std::int64_t kFramePeriodNs = 33'333'333;  // 30 fps
  static constexpr std::int64_t kFrameDelayNs = 5'000'000;    // the first frame after state 0
  static constexpr std::int64_t kDecodeNs = 3'000'000;        // received -> decoded
  static constexpr std::int64_t kLogNs = 100'000'000;         // the log line's time

  // State k's measured joints (rad), its velocity, its gripper opening.
  static Eigen::VectorXd q(int k) {
    Eigen::VectorXd q(6);
    for (int i = 0; i < 6; ++i) q[i] = 0.1 * (i + 1) + 0.2 * std::sin(0.05 * k + i);
    return q;
  }
  static Eigen::VectorXd qd(int k) { return Eigen::VectorXd::Constant(6, 0.01 * k); }
  static double gripper(int k) { return 0.5 + 0.01 * (k % 10); }
  static Eigen::VectorXd ghost(int k) { return q(k) + Eigen::VectorXd::Constant(6, 0.05); }
  // Frame j's latency by stage (s): the network stage varies, the others are constant.
  static net::StageLatency latency(int j) {
    net::StageLatency l;
    l.capture_to_encode_s = 0.004;
    l.encode_s = 0.002;
    l.send_queue_s = 0.0005;
    l.network_s = 0.001 + 0.0001 * (j % 5);
    l.decode_s = 0.0025;
    l.total_s = l.capture_to_encode_s + l.encode_s + l.send_queue_s + l.network_s + l.decode_s;
    return l;
  }
};

// Writes it to `path`; `base_ns` (client clock) is state 0's receipt.
inline Result<record::RecordingCounts> write_synthetic_recording(const std::string& path,
                                                                 const SyntheticRecording& r,
                                                                 std::int64_t base_ns = 0) {
  if (base_ns == 0) base_ns = core::monotonic_ns();
  auto description = core::load_robot_description({"puma560"});
  if (!description) return description.error();
  record::RecordedSetup setup;
  setup.robot.model_name = "puma560";
  setup.robot.urdf = core::urdf_text_for_clients(*description);
  for (const core::Joint& j : description->model->joints()) setup.robot.joints.push_back({j.name});
  record::SessionRecorderOptions options;
  options.path = path;
  options.mcap.chunk_size = r.chunk_size;
  options.metadata["recorded_by"] = "synthetic_recording.hpp";
  auto recorder = record::SessionRecorder::create(options, setup);
  if (!recorder) return recorder.error();

  // In time order, as a live session hands them over.
  const std::string left(r.left_bytes, '\x11'), right(r.right_bytes, '\x22');
  int next_frame = 0;
  const auto frames_until = [&](std::int64_t t) {
    for (; next_frame < r.frames; ++next_frame) {
      const std::int64_t received = base_ns + SyntheticRecording::kFrameDelayNs +
                                    next_frame * SyntheticRecording::kFramePeriodNs;
      if (received > t) break;
      net::ReceivedStereoFrame f;
      f.frame_id = static_cast<std::uint64_t>(next_frame + 1);
      f.jpeg_left = &left;
      f.jpeg_right = &right;
      f.capture_ns_left = f.capture_ns_right = received - 10'000'000;
      f.receive_ns = received;
      (*recorder)->add_frame(f);
      net::DecodedStereoFrame d;
      d.frame_id = f.frame_id;
      d.capture_ns_left = d.capture_ns_right = f.capture_ns_left;
      d.decoded_ns = received + SyntheticRecording::kDecodeNs;
      d.latency = SyntheticRecording::latency(next_frame);
      (*recorder)->add_latency(d);
    }
  };
  bool logged = false;
  for (int k = 0; k < r.states; ++k) {
    const std::int64_t t = base_ns + k * SyntheticRecording::kStatePeriodNs;
    frames_until(t);
    if (!logged && t >= base_ns + SyntheticRecording::kLogNs) {
      logged = true;
      (*recorder)->add_log(record::LogLevel::kWarning, r.log_line,
                           base_ns + SyntheticRecording::kLogNs);
    }
    net::RobotStateSample s;
    s.sequence = static_cast<std::uint64_t>(k + 1);
    s.receive_ns = t;
    s.capture_ns = t - 2'000'000;
    s.state.q = SyntheticRecording::q(k);
    s.state.qd = SyntheticRecording::qd(k);
    s.state.q_commanded = s.state.q + r.command_offset;
    s.state.qd_commanded = s.state.qd;
    s.state.gripper = SyntheticRecording::gripper(k);
    s.state.gripper_target = s.state.gripper;
    s.lease_holder = "operator";
    s.ghost_q = SyntheticRecording::ghost(k);
    s.ghost_gripper = 0.25;
    s.ghost_ns = s.capture_ns;
    (*recorder)->add_state(s);
  }
  frames_until(std::numeric_limits<std::int64_t>::max());
  return (*recorder)->close();
}

}  // namespace telear::test
