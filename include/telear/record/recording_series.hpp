#pragma once
// A recording's streams as time series: what `telear report` plots and `telear replay` looks
// up by time. One pass over an MCAP file that SessionRecorder wrote (topics:
// telear/record/recording_topics.hpp), every message decoded with the generated protobuf
// classes; camera frames are indexed (time, size), not kept: replay reads their JPEG bytes
// when it shows them.
//
// Times. `t` is seconds since the recording's first message (its log time, the recorder's wall
// clock); `log_ns` the message's log time itself (for McapReadOptions' time range).

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/net/latency_stages.hpp"
#include "telear/record/session_recorder.hpp"

namespace telear::record {

struct JointSample {
  double t = 0.0;
  std::uint64_t log_ns = 0;
  std::int64_t stamp_ns = 0;      // the message's timestamp field (the state's time)
  Eigen::VectorXd position;       // the arm's joints, in `JointSeries::names` order
  Eigen::VectorXd velocity;       // empty when the message carries none
  std::optional<double> gripper;  // the "gripper" joint: opening 0..1
};

struct JointSeries {
  std::vector<std::string> names;    // the arm's joints (the gripper not among them)
  std::vector<JointSample> samples;  // in log time order
  // The newest sample at or before log time `log_ns`; null before the first.
  const JointSample* at(std::uint64_t log_ns) const;
};

struct LatencySample {
  double t = 0.0;
  std::uint64_t log_ns = 0;   // when the view first drew the frame, else when it was decoded
  std::int64_t stamp_ns = 0;  // the pair's capture time (the later eye's): its frames' stamps
  std::uint64_t frame_id = 0;
  std::array<double, net::kLatencyStageCount> stages{};  // seconds, kLatencyStages' order
  std::optional<double> decoded_to_shown_s;
};

struct FrameSample {
  double t = 0.0;
  std::uint64_t log_ns = 0;
  std::int64_t stamp_ns = 0;  // the capture time (CompressedImage.timestamp)
  std::size_t bytes = 0;      // the JPEG's size
};

struct EventSample {
  double t = 0.0;
  LogLevel level = LogLevel::kInfo;
  std::string text;
};

struct PlanEventSample {
  double t = 0.0;
  int kind = 0;           // telear.record.v1.PlanEvent.Kind
  std::string kind_name;  // its enum name: "DISPLAY_MODE", "EXECUTE", ...
  std::string text, plan_id, plan_hash;
};

struct RecordingSeries {
  std::string path;
  bool complete = true;  // false: the file had no summary (a killed recorder), read by scanning
  std::uint64_t start_ns = 0, end_ns = 0;  // first and last log time
  double duration_s() const { return (end_ns - start_ns) * 1e-9; }
  JointSeries robot;                               // /robot/joint_states
  JointSeries commands;                            // /robot/joint_commands
  JointSeries ghost;                               // /ghost/joint_states
  std::vector<LatencySample> latency;              // /telear/latency
  std::array<std::vector<FrameSample>, 2> frames;  // left, right image topics
  std::vector<EventSample> events;                 // /events
  std::vector<PlanEventSample> plan_events;        // /telear/plan_events
  // By record name; a later record of a name adds to (and overrides keys of) an earlier one.
  std::map<std::string, std::map<std::string, std::string>> metadata;
  // Messages per topic, every channel of the file (0 included): the file's statistics, or for
  // a file without a summary the count of its complete chunks' messages.
  std::map<std::string, std::uint64_t> message_counts;
  std::string urdf;              // the robot.urdf attachment (empty: none)
  std::string calibration_yaml;  // the calibration.yaml attachment (empty: none)
};

// Errors: the file (McapReader's message: not MCAP, truncated, CRC), a channel of one of the
// topics above whose schema is another, a message that does not parse with its topic's schema
// (the topic, the message's sequence number and log time named).
Result<RecordingSeries> load_recording_series(const std::string& path);

}  // namespace telear::record
