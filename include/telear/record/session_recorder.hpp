#pragma once
// SessionRecorder: a session's streams into one MCAP file with Foxglove's schemas (topics:
// telear/record/recording_topics.hpp; docs/recording.md).
//
// Never slows the operator. The add_* calls copy what they are given into a bounded queue and
// return; a writer thread converts each item to its protobuf message and writes it
// (McapWriter: zstd chunks, flushed as they fill, so a crash or a kill loses at most the
// chunk being filled). When the queue holds `queue_bytes`, new items are dropped and counted
// (per topic); close() writes the counts into the file (metadata "telear.recording" and a
// warning on /events), so a reader knows what is missing.
//
// Time. Every timestamp is on the recording machine's wall clock (what Foxglove's timeline
// shows): the client clock (monotonic, telear's stamps after the clock-offset conversion)
// plus the wall-minus-monotonic offset read once when the recorder is created. A message's
// log time is when it reached the recorder; its timestamp field is the capture time.

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "telear/core/result.hpp"
#include "telear/net/robot_client.hpp"
#include "telear/net/vision_client.hpp"
#include "telear/record/mcap_writer.hpp"
#include "telear/vision/camera_model.hpp"

namespace telear::record {

struct SessionRecorderOptions {
  std::string path;                      // the .mcap file (created, truncated)
  std::size_t queue_bytes = 256u << 20;  // items waiting for the writer thread
  McapWriterOptions mcap;
  // Written as metadata "telear.session" besides the robot and the cameras' file names.
  std::map<std::string, std::string> metadata;
  // Where /ghost/joint_states comes from: the state stream's ghost (the lease holder's, as its
  // heartbeat last carried it: what a passive observer sees), or false: the caller's
  // add_ghost() (the operator's own program, once per displayed frame: what the view drew).
  bool ghost_from_state_stream = true;
};

// What the recorder knows of the arm and the cameras: the robot server's GetInfo (its URDF,
// attached as robot.urdf, gives the link names of /tf), the vision server's GetCameraInfo.
struct RecordedSetup {
  net::RobotInfo robot;
  std::optional<vision::StereoCameraModel> cameras;
  std::string calibration_yaml;  // attached as calibration.yaml when not empty
};

// Per topic: messages written, and items dropped because the queue was full.
struct RecordingCounts {
  std::map<std::string, std::uint64_t> written;
  std::map<std::string, std::uint64_t> dropped;
  std::uint64_t bytes = 0;  // the file's size after close()
};

enum class LogLevel { kDebug, kInfo, kWarning, kError };

// telear.record.v1.PlanEvent's kinds (proto/telear/record/v1/plan_event.proto), numbered as
// there; the header stays free of generated code.
enum class PlanEventKind {
  kLeaseAcquired = 1,
  kLeaseReleased = 2,
  kPreview = 3,
  kValidate = 4,
  kExecute = 5,
  kCollision = 6,
  kDisplayMode = 7,
  kEStop = 8,
  kEStopReset = 9,
  kFault = 10,
};

class SessionRecorder {
 public:
  // Opens the file and writes the schemas, channels, attachments and metadata. Errors: the
  // file cannot be created, the robot's URDF does not parse.
  static Result<std::unique_ptr<SessionRecorder>> create(const SessionRecorderOptions& options,
                                                         const RecordedSetup& setup);
  ~SessionRecorder();  // close()s
  SessionRecorder(const SessionRecorder&) = delete;
  SessionRecorder& operator=(const SessionRecorder&) = delete;

  // Thread-safe, never blocking on the file.
  void add_frame(const net::ReceivedStereoFrame& frame);  // both eyes' JPEGs, as received
  void add_state(const net::RobotStateSample& sample);    // joints, ghost, link transforms
  // The frame's latency by stage, logged when it was decoded, or at `shown_ns` (client clock)
  // when an operator's view drew it first: replay then shows at time t the frame the view had.
  void add_latency(const net::DecodedStereoFrame& frame,
                   std::optional<std::int64_t> shown_ns = std::nullopt);
  void add_log(LogLevel level, const std::string& text, std::int64_t client_ns);
  // A workflow event on /telear/plan_events, and as a Log on /events (level by kind).
  void add_plan_event(PlanEventKind kind, const std::string& text, const std::string& plan_id,
                      const std::string& plan_hash, std::int64_t client_ns);
  // The ghost as the operator's view drew it (ghost_from_state_stream false): on
  // /ghost/joint_states and as ghost/ frames on /tf. A robot state that finds no ghost written
  // in the last 15 ms writes the last one again at its own time (a display slower than the
  // state stream), so the topic keeps at least the state stream's rate. Ignored with
  // ghost_from_state_stream.
  void add_ghost(const Eigen::VectorXd& q, double gripper, std::int64_t client_ns);

  // Drains the queue, writes the counts and the file's summary; a second call returns the
  // same counts. Errors: a failed write (the file is then what was written before it).
  Result<RecordingCounts> close();

  // A client-clock (monotonic) time on the recording's wall clock: a message's log time.
  std::int64_t wall_ns(std::int64_t client_ns) const;

  // Counts so far (written ones as the writer thread has written them).
  RecordingCounts counts() const;

 private:
  struct Impl;
  explicit SessionRecorder(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace telear::record
