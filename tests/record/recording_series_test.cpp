// RecordingSeries: a recording SessionRecorder wrote (tests/record/synthetic_recording.hpp: known
// states, commands, ghost, frames, latency, events) read back as time series -- counts, values
// and times as written; a file cut short reads up to its last complete chunk; a file that is not
// MCAP is an error naming it.

#include "telear/record/recording_series.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "foxglove/JointStates.pb.h"
#include "record/synthetic_recording.hpp"
#include "telear/record/mcap_writer.hpp"
#include "telear/record/recording_topics.hpp"
#include "telear/record/schema_descriptors.hpp"
#include "test_util/temp_dir.hpp"

namespace telear::record {
namespace {

using test::SyntheticRecording;
using ::testing::HasSubstr;

TEST(RecordingSeries, ReadsBackWhatTheRecorderWrote) {
  test_files::TempDir tmp("recording_series");
  const std::string path = tmp.file("synthetic.mcap");
  SyntheticRecording r;
  r.command_offset[1] = 0.01;
  auto counts = test::write_synthetic_recording(path, r);
  ASSERT_TRUE(counts) << counts.error().message;

  auto series = load_recording_series(path);
  ASSERT_TRUE(series) << series.error().message;
  EXPECT_TRUE(series->complete);
  EXPECT_EQ(series->path, path);

  // Counts: every message of every topic the series holds, as the recorder counted them.
  const auto n = static_cast<std::size_t>(r.states);
  EXPECT_EQ(series->robot.samples.size(), n);
  EXPECT_EQ(series->commands.samples.size(), n);
  EXPECT_EQ(series->ghost.samples.size(), n);
  EXPECT_EQ(series->frames[0].size(), static_cast<std::size_t>(r.frames));
  EXPECT_EQ(series->frames[1].size(), static_cast<std::size_t>(r.frames));
  EXPECT_EQ(series->latency.size(), static_cast<std::size_t>(r.frames));
  for (const auto& [topic, written] : counts->written) {
    EXPECT_EQ(series->message_counts[topic], written) << topic;
  }
  EXPECT_EQ(series->message_counts[std::string(kTopicWorkspace)], 0u);  // every channel listed

  // Values: the arm's joints by name, the gripper apart; commands, velocities, the ghost.
  ASSERT_EQ(series->robot.names.size(), 6u);
  EXPECT_EQ(series->robot.names[0], "waist");
  EXPECT_EQ(series->robot.names[1], "shoulder");
  EXPECT_EQ(series->commands.names, series->robot.names);
  for (int k : {0, 17, r.states - 1}) {
    const JointSample& measured = series->robot.samples[static_cast<std::size_t>(k)];
    const JointSample& command = series->commands.samples[static_cast<std::size_t>(k)];
    EXPECT_TRUE(measured.position.isApprox(SyntheticRecording::q(k), 1e-15)) << k;
    EXPECT_TRUE(measured.velocity.isApprox(SyntheticRecording::qd(k), 1e-15)) << k;
    ASSERT_TRUE(measured.gripper.has_value());
    EXPECT_DOUBLE_EQ(*measured.gripper, SyntheticRecording::gripper(k));
    EXPECT_NEAR(command.position[1] - measured.position[1], 0.01, 1e-12) << k;
    EXPECT_NEAR(command.position[0] - measured.position[0], 0.0, 1e-12) << k;
    const JointSample& ghost = series->ghost.samples[static_cast<std::size_t>(k)];
    EXPECT_TRUE(ghost.position.isApprox(SyntheticRecording::ghost(k), 1e-15)) << k;
    EXPECT_EQ(ghost.velocity.size(), 0);  // the ghost carries none
    EXPECT_DOUBLE_EQ(ghost.gripper.value_or(-1), 0.25);
  }
  EXPECT_EQ(series->frames[0][3].bytes, r.left_bytes);
  EXPECT_EQ(series->frames[1][3].bytes, r.right_bytes);
  const net::StageLatency expected = SyntheticRecording::latency(7);
  EXPECT_EQ(series->latency[7].frame_id, 8u);
  EXPECT_DOUBLE_EQ(series->latency[7].stages[3], expected.network_s);
  EXPECT_DOUBLE_EQ(series->latency[7].stages[net::kTotalLatencyStage], expected.total_s);
  EXPECT_FALSE(series->latency[7].decoded_to_shown_s.has_value());

  // Times: t from the first message -- the lease taken, a plan event stamped with state 0's
  // capture time, 2 ms before its receipt (the states' log time) -- then the states every
  // 20 ms, frames every 33.3 ms from 5 ms after state 0; a state's stamp is its capture time.
  EXPECT_DOUBLE_EQ(series->plan_events[0].t, 0.0);
  EXPECT_EQ(series->start_ns + 2'000'000, series->robot.samples[0].log_ns);
  for (std::size_t k = 0; k < n; ++k) {
    const JointSample& s = series->robot.samples[k];
    EXPECT_NEAR(s.t, 0.002 + static_cast<double>(k) * 0.020, 1e-9) << k;
    EXPECT_EQ(static_cast<std::int64_t>(s.log_ns) - s.stamp_ns, 2'000'000) << k;
  }
  EXPECT_NEAR(series->frames[0][2].t, 0.002 + 0.005 + 2 * 0.033333333, 1e-9);
  EXPECT_NEAR(series->latency[2].t, 0.002 + 0.005 + 2 * 0.033333333 + 0.003, 1e-9);
  EXPECT_NEAR(series->duration_s(), 0.002 + std::max(0.98, 0.005 + 29 * 0.033333333 + 0.003), 1e-9);

  // at(): the newest sample at or before a log time.
  const JointSeries& robot = series->robot;
  EXPECT_EQ(robot.at(robot.samples[0].log_ns - 1), nullptr);
  EXPECT_EQ(robot.at(robot.samples[0].log_ns), &robot.samples[0]);
  EXPECT_EQ(robot.at(robot.samples[10].log_ns + 1), &robot.samples[10]);
  EXPECT_EQ(robot.at(robot.samples[11].log_ns - 1), &robot.samples[10]);
  EXPECT_EQ(robot.at(std::numeric_limits<std::uint64_t>::max()), &robot.samples.back());

  // Events, plan events (the lease seen in the state stream), attachments and metadata.
  ASSERT_FALSE(series->events.empty());
  bool logged = false;
  for (const EventSample& e : series->events) {
    if (e.text != r.log_line) continue;
    logged = true;
    EXPECT_EQ(e.level, LogLevel::kWarning);
    EXPECT_NEAR(e.t, 0.002 + 0.1, 1e-9);
  }
  EXPECT_TRUE(logged);
  ASSERT_FALSE(series->plan_events.empty());
  EXPECT_EQ(series->plan_events[0].kind_name, "LEASE_ACQUIRED");
  EXPECT_EQ(series->plan_events[0].kind, 1);
  EXPECT_EQ(series->plan_events[0].text, "operator holds the lease");
  EXPECT_THAT(series->urdf, HasSubstr("<robot"));
  EXPECT_TRUE(series->calibration_yaml.empty());  // none given to the recorder
  EXPECT_EQ(series->metadata["telear.session"]["robot"], "puma560");
  EXPECT_EQ(series->metadata["telear.recording"]["dropped_total"], "0");
}

TEST(RecordingSeries, AFileCutShortReadsUpToItsLastCompleteChunk) {
  test_files::TempDir tmp("recording_series_cut");
  const std::string path = tmp.file("whole.mcap");
  SyntheticRecording r;
  r.chunk_size = 8 * 1024;  // several chunks
  auto counts = test::write_synthetic_recording(path, r);
  ASSERT_TRUE(counts) << counts.error().message;
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string cut = tmp.file("cut.mcap");
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() * 6 / 10);

  auto series = load_recording_series(cut);
  ASSERT_TRUE(series) << series.error().message;
  EXPECT_FALSE(series->complete);
  // The chunks before the cut: some states, not all; in order, each with its command.
  EXPECT_GT(series->robot.samples.size(), 5u);
  EXPECT_LT(series->robot.samples.size(), static_cast<std::size_t>(r.states));
  EXPECT_EQ(series->commands.samples.size(), series->robot.samples.size());
  for (std::size_t k = 0; k < series->robot.samples.size(); ++k) {
    EXPECT_TRUE(series->robot.samples[k].position.isApprox(
        SyntheticRecording::q(static_cast<int>(k)), 1e-15))
        << k;
  }
  EXPECT_EQ(series->message_counts[std::string(kTopicRobotJointStates)],
            series->robot.samples.size());
  // The recorder's closing metadata is after the cut; the attachment before it.
  EXPECT_EQ(series->metadata.count("telear.recording"), 0u);
  EXPECT_FALSE(series->urdf.empty());
}

TEST(RecordingSeries, AFileThatIsNotMcapIsAnErrorNamingIt) {
  test_files::TempDir tmp("recording_series_bad");
  const std::string path = tmp.write("notes.mcap", "these are not the bytes of an MCAP file\n");
  auto series = load_recording_series(path);
  ASSERT_FALSE(series);
  EXPECT_THAT(series.error().message, HasSubstr("'" + path + "'"));
  EXPECT_THAT(series.error().message, HasSubstr("not an MCAP file"));
  auto missing = load_recording_series(tmp.file("missing.mcap"));
  ASSERT_FALSE(missing);
  EXPECT_THAT(missing.error().message, HasSubstr("missing.mcap"));
}

// Bytes that are MCAP but not telear's: a known topic under another schema, a message that does
// not parse as its schema. Each is an error naming the topic.
TEST(RecordingSeries, AChannelOrMessageThatDoesNotDecodeIsAnErrorNamingTheTopic) {
  test_files::TempDir tmp("recording_series_undecodable");
  const auto write = [&tmp](const std::string& name, const std::string& schema_name,
                            const std::string& message) {
    const std::string path = tmp.file(name);
    auto writer = McapWriter::open(path);
    EXPECT_TRUE(writer) << writer.error().message;
    const SchemaInfo schema = schema_for<foxglove::JointStates>();
    const std::uint16_t channel = writer->add_channel(
        writer->add_schema(schema_name, schema.encoding, mcap_bytes(schema.data)),
        kTopicRobotJointStates, kProtobufEncoding);
    EXPECT_TRUE(writer->write(channel, 1, 1000, 1000, mcap_bytes(message)));
    EXPECT_TRUE(writer->close());
    return path;
  };
  const std::string other = write("other.mcap", "foxglove.Log", "");
  auto series = load_recording_series(other);
  ASSERT_FALSE(series);
  EXPECT_EQ(series.error().message, "recording '" + other +
                                        "': topic /robot/joint_states has schema 'foxglove.Log', "
                                        "expected foxglove.JointStates");
  // A field tag of 0 is never valid protobuf.
  const std::string garbage = write("garbage.mcap", "foxglove.JointStates", std::string(4, '\0'));
  series = load_recording_series(garbage);
  ASSERT_FALSE(series);
  EXPECT_EQ(series.error().message,
            "recording '" + garbage +
                "': message 1 on /robot/joint_states (log time 1000 ns) does not parse as "
                "foxglove.JointStates");
}

}  // namespace
}  // namespace telear::record
