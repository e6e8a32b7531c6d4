#pragma once
// ServerRecorder: records running servers to MCAP as a passive observer (no lease) -- the
// engine of `telear record`, `telear demo --record` and `telear console --record`. It opens its
// own robot client (the state stream at `state_rate_hz`, which carries the lease holder's
// ghost) and vision client (each frame's JPEGs as received, and its latency once decoded),
// reads the servers' info (URDF, workspace, calibration) and feeds a SessionRecorder from a
// thread of its own. An operator's program adds its own events with add_log().

#include <map>
#include <memory>
#include <optional>
#include <string>

#include "telear/core/result.hpp"
#include "telear/record/session_recorder.hpp"

namespace telear::record {

struct ServerRecorderOptions {
  std::string robot_address;   // HOST:PORT
  std::string vision_address;  // HOST:PORT; empty: no video
  std::string token;           // the servers' bearer token
  std::string tls_ca_file;     // TLS: the CA the servers' certificates are signed by
  std::string client_name = "telear-record";
  double state_rate_hz = 50.0;  // 1..250 (the robot server's bounds)
  // false: no video stream of its own -- the caller feeds add_frame() and add_latency() from
  // the vision client it already has (the console, the demo: a second stream would decode
  // every frame twice on the operator's machine). The calibration is still asked for.
  bool stream_video = true;
  // false: no state stream of its own -- the caller feeds add_state() every state its robot
  // client receives (RobotClientOptions::on_state: the console's, the demo's session), so that
  // the recording holds the very states the view drew the real arm at. The robot's info is
  // still asked for.
  bool stream_state = true;
  // The calibration the operator's view draws through (the console's or the demo's registered
  // cameras), recorded instead of the vision server's: replay draws through what was seen.
  std::optional<vision::StereoCameraModel> cameras;
  SessionRecorderOptions recorder;  // path, queue, metadata
};

class ServerRecorder {
 public:
  // Connects, reads the servers' info, opens the file and starts recording. Errors: a server
  // that does not answer (named), the file, the URDF.
  static Result<std::unique_ptr<ServerRecorder>> start(const ServerRecorderOptions& options);
  ~ServerRecorder();  // stop()s
  ServerRecorder(const ServerRecorder&) = delete;
  ServerRecorder& operator=(const ServerRecorder&) = delete;

  void add_log(LogLevel level, const std::string& text, std::int64_t client_ns);
  // With stream_video false: the caller's frames (VisionClientOptions::on_received) and their
  // latency once decoded. Thread-safe, never blocking.
  void add_frame(const net::ReceivedStereoFrame& frame);
  // With stream_state false: the caller's states (RobotClientOptions::on_state), every one.
  void add_state(const net::RobotStateSample& sample);
  void add_latency(const net::DecodedStereoFrame& frame,
                   std::optional<std::int64_t> shown_ns = std::nullopt);
  // SessionRecorder's, for the operator's program (telear/session/session_recording.hpp).
  void add_plan_event(PlanEventKind kind, const std::string& text, const std::string& plan_id,
                      const std::string& plan_hash, std::int64_t client_ns);
  void add_ghost(const Eigen::VectorXd& q, double gripper, std::int64_t client_ns);
  std::int64_t wall_ns(std::int64_t client_ns) const;  // SessionRecorder::wall_ns
  // Stops the clients, then closes the file (SessionRecorder::close). A second call returns
  // the same counts.
  Result<RecordingCounts> stop();

 private:
  struct Impl;
  explicit ServerRecorder(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace telear::record
