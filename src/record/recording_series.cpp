#include "telear/record/recording_series.hpp"

#include <google/protobuf/timestamp.pb.h>

#include <algorithm>
#include <functional>
#include <limits>
#include <optional>
#include <unordered_map>

#include "foxglove/CompressedImage.pb.h"
#include "foxglove/JointStates.pb.h"
#include "foxglove/Log.pb.h"
#include "telear/record/mcap_reader.hpp"
#include "telear/record/recording_topics.hpp"
#include "telear/record/v1/latency_stages.pb.h"
#include "telear/record/v1/plan_event.pb.h"

namespace telear::record {

const JointSample* JointSeries::at(std::uint64_t log_ns) const {
  const auto after = std::upper_bound(
      samples.begin(), samples.end(), log_ns,
      [](std::uint64_t t, const JointSample& sample) { return t < sample.log_ns; });
  return after == samples.begin() ? nullptr : &*std::prev(after);
}

namespace {

// The recorder's gripper: one JointState named so, its opening fraction (session_recorder.cpp).
constexpr std::string_view kGripperJoint = "gripper";

std::int64_t stamp_ns(const google::protobuf::Timestamp& t) {
  return t.seconds() * 1'000'000'000 + t.nanos();
}

LogLevel log_level(foxglove::Log::Level level) {
  switch (level) {
    case foxglove::Log::DEBUG:
      return LogLevel::kDebug;
    case foxglove::Log::WARNING:
      return LogLevel::kWarning;
    case foxglove::Log::ERROR:
    case foxglove::Log::FATAL:
      return LogLevel::kError;
    default:
      return LogLevel::kInfo;
  }
}

// One JointStates message into its series: the names come from the series' first message (the
// gripper apart); a later message's joints are placed by name, so a joint it lacks reads NaN.
void add_joints(const foxglove::JointStates& message, std::uint64_t log_ns, double t,
                JointSeries& series) {
  if (series.samples.empty()) {
    for (const foxglove::JointState& j : message.joints()) {
      if (j.name() != kGripperJoint) series.names.push_back(j.name());
    }
  }
  const auto n = static_cast<Eigen::Index>(series.names.size());
  JointSample sample;
  sample.t = t;
  sample.log_ns = log_ns;
  sample.stamp_ns = stamp_ns(message.timestamp());
  sample.position = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::quiet_NaN());
  Eigen::VectorXd velocity = sample.position;
  bool any_velocity = false;
  for (int k = 0; k < message.joints_size(); ++k) {
    const foxglove::JointState& j = message.joints(k);
    if (j.name() == kGripperJoint) {
      if (j.has_position()) sample.gripper = j.position();
      continue;
    }
    // Joints in the first message's order are the usual case: look there first.
    Eigen::Index i = k < n && series.names[static_cast<std::size_t>(k)] == j.name() ? k : -1;
    if (i < 0) {
      const auto it = std::find(series.names.begin(), series.names.end(), j.name());
      if (it == series.names.end()) continue;
      i = it - series.names.begin();
    }
    if (j.has_position()) sample.position[i] = j.position();
    if (j.has_velocity()) {
      velocity[i] = j.velocity();
      any_velocity = true;
    }
  }
  if (any_velocity) sample.velocity = std::move(velocity);
  series.samples.push_back(std::move(sample));
}

}  // namespace

Result<RecordingSeries> load_recording_series(const std::string& path) {
  auto reader = McapReader::open(path);
  if (!reader) return reader.error();
  RecordingSeries series;
  series.path = path;
  series.complete = reader->complete();
  const McapStatistics& statistics = reader->statistics();
  series.start_ns = statistics.message_start_time;
  series.end_ns = std::max(statistics.message_end_time, statistics.message_start_time);
  for (const auto& [id, channel] : reader->channels()) {
    const auto count = statistics.channel_message_counts.find(id);
    series.message_counts[channel.topic] +=
        count == statistics.channel_message_counts.end() ? 0 : count->second;
  }

  // Each topic the series holds, with its schema's generated class: a message that does not
  // parse, or a channel whose schema is another, is an error naming the topic.
  foxglove::JointStates joints;
  foxglove::CompressedImage image;
  foxglove::Log log;
  telear::record::v1::LatencyStages latency;
  telear::record::v1::PlanEvent plan_event;
  struct Decoder {
    google::protobuf::Message* message;
    std::function<void(const McapMessageView&, double t)> add;
  };
  const auto frame_adder = [&](std::size_t eye) {
    return [&series, &image, eye](const McapMessageView& m, double t) {
      series.frames[eye].push_back(
          {t, m.log_time, stamp_ns(image.timestamp()), image.data().size()});
    };
  };
  std::unordered_map<std::string_view, Decoder> decoders = {
      {kTopicRobotJointStates,
       {&joints, [&](const McapMessageView& m,
                     double t) { add_joints(joints, m.log_time, t, series.robot); }}},
      {kTopicRobotJointCommands,
       {&joints, [&](const McapMessageView& m,
                     double t) { add_joints(joints, m.log_time, t, series.commands); }}},
      {kTopicGhostJointStates,
       {&joints, [&](const McapMessageView& m,
                     double t) { add_joints(joints, m.log_time, t, series.ghost); }}},
      {kTopicLeftImage, {&image, frame_adder(0)}},
      {kTopicRightImage, {&image, frame_adder(1)}},
      {kTopicLatency,
       {&latency,
        [&](const McapMessageView& m, double t) {
          LatencySample sample;
          sample.t = t;
          sample.log_ns = m.log_time;
          sample.stamp_ns = stamp_ns(latency.timestamp());
          sample.frame_id = latency.frame_id();
          net::StageLatency stages;
          stages.capture_to_encode_s = latency.capture_to_encode_s();
          stages.encode_s = latency.encode_s();
          stages.send_queue_s = latency.send_queue_s();
          stages.network_s = latency.network_s();
          stages.decode_s = latency.decode_s();
          stages.total_s = latency.total_s();
          for (std::size_t i = 0; i < net::kLatencyStageCount; ++i) {
            sample.stages[i] = net::kLatencyStages[i].of(stages);
          }
          if (latency.has_decoded_to_shown_s()) {
            sample.decoded_to_shown_s = latency.decoded_to_shown_s();
          }
          series.latency.push_back(sample);
        }}},
      {kTopicEvents,
       {&log,
        [&](const McapMessageView&, double t) {
          series.events.push_back({t, log_level(log.level()), log.message()});
        }}},
      {kTopicPlanEvents,
       {&plan_event,
        [&](const McapMessageView&, double t) {
          series.plan_events.push_back(
              {t, plan_event.kind(), telear::record::v1::PlanEvent::Kind_Name(plan_event.kind()),
               plan_event.text(), plan_event.plan_id(), plan_event.plan_hash()});
        }}},
  };

  McapReadOptions options;
  for (const auto& [id, channel] : reader->channels()) {
    const auto decoder = decoders.find(channel.topic);
    if (decoder == decoders.end()) continue;
    const auto schema = reader->schemas().find(channel.schema_id);
    const std::string expected = decoder->second.message->GetDescriptor()->full_name();
    if (schema == reader->schemas().end() || schema->second.name != expected) {
      return Error{"recording '" + path + "': topic " + channel.topic + " has schema '" +
                   (schema == reader->schemas().end() ? std::string() : schema->second.name) +
                   "', expected " + expected};
    }
    options.topics.push_back(channel.topic);
  }
  std::optional<Error> bad_message;
  if (!options.topics.empty()) {
    Status read = reader->read_messages(
        [&](const McapMessageView& m) {
          const Decoder& decoder = decoders.at(m.topic);
          if (!decoder.message->ParseFromArray(m.data.data(), static_cast<int>(m.data.size()))) {
            bad_message =
                Error{"recording '" + path + "': message " + std::to_string(m.sequence) + " on " +
                      std::string(m.topic) + " (log time " + std::to_string(m.log_time) +
                      " ns) does not parse as " + decoder.message->GetDescriptor()->full_name()};
            return false;
          }
          decoder.add(m, static_cast<double>(m.log_time - series.start_ns) * 1e-9);
          return true;
        },
        options);
    if (!read) return read.error();
    if (bad_message) return *bad_message;
  }

  auto metadata = reader->metadata();
  if (!metadata) return metadata.error();
  for (McapMetadata& record : *metadata) {
    for (auto& [key, value] : record.entries) series.metadata[record.name][key] = value;
  }
  auto attachments = reader->attachments();
  if (!attachments) return attachments.error();
  for (const McapAttachment& a : *attachments) {
    std::string text(a.data.begin(), a.data.end());
    if (a.name == "robot.urdf") series.urdf = std::move(text);
    if (a.name == "calibration.yaml") series.calibration_yaml = std::move(text);
  }
  return series;
}

}  // namespace telear::record
