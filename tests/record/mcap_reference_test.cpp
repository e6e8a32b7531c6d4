// The MCAP writer against the reference reader: files written here are read by npm's
// @mcap/core (Foxglove's TypeScript implementation, tests/record/js/read_mcap.mjs under node),
// both through the index (footer, summary, chunk and message indexes) and as a stream, and
// every message it returns is compared with what was written (times and SHA-256 of the bytes,
// from a sidecar JSON this test writes). Then the same recording cut at seeded random offsets,
// as a killed recorder leaves it: the streaming reader must still return exactly the messages
// of the chunks completed before the cut.
//
// Needs node (scripts/install-deps.sh) and tests/record/js/node_modules (`npm ci --prefix
// tests/record/js`, which scripts/test.sh runs).

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "mcap_test_records.hpp"
#include "telear/core/sha256.hpp"
#include "telear/record/mcap_writer.hpp"
#include "test_util/temp_dir.hpp"

namespace telear::record {
namespace {

using nlohmann::json;

struct WrittenMessage {
  std::string topic;
  std::uint32_t sequence = 0;
  std::uint64_t log_time = 0;
  std::uint64_t publish_time = 0;
  std::string sha256;
  std::uint32_t chunk = 0;  // the chunk it went into: 0, 1, ... in file order
};

struct Recording {
  std::vector<WrittenMessage> messages;
  McapStatistics statistics;
  std::string attachment_sha256;
};

constexpr std::uint64_t kStart = 1'700'000'000'000'000'000ull;  // ns, a plausible Unix time
const char* const kUrdf = "<robot name=\"puma560\"><link name=\"base\"/></robot>\n";

// Four seconds of a session: joint states at 500 Hz, transforms at 100 Hz, camera frames at
// 30 Hz (incompressible bytes, like JPEG), a few events; metadata after 1 s and the robot's URDF
// attached after 2 s. ~2550 messages, ~1 MB, about 16 chunks of 64 KiB.
Recording write_session(const std::string& path, McapCompression compression) {
  Recording out;
  McapWriterOptions options;
  options.library = "telear mcap_reference_test";
  options.compression = compression;
  options.chunk_size = 64 * 1024;
  auto writer = McapWriter::open(path, options);
  EXPECT_TRUE(writer.ok()) << writer.error().message;
  if (!writer.ok()) return out;
  const std::uint16_t joints_schema =
      writer->add_schema("telear.JointStates", "jsonschema", mcap_bytes("{\"type\":\"object\"}"));
  const std::uint16_t image_schema = writer->add_schema(
      "foxglove.CompressedImage", "jsonschema", mcap_bytes("{\"type\":\"object\",\"x\":1}"));
  struct Topic {
    std::uint16_t channel;
    std::string name;
    std::uint64_t period_ms;
    std::uint32_t sequence = 0;
  };
  std::vector<Topic> topics = {
      {writer->add_channel(joints_schema, "/joint_states", "json", {{"robot", "puma560"}}),
       "/joint_states", 2},
      {writer->add_channel(joints_schema, "/tf", "json"), "/tf", 10},
      {writer->add_channel(image_schema, "/camera/left/compressed", "json", {{"fps", "30"}}),
       "/camera/left/compressed", 33},
      {writer->add_channel(0, "/events", "", {}), "/events", 157},
  };
  std::mt19937_64 rng(2024);
  for (std::uint64_t ms = 0; ms < 4000; ++ms) {
    if (ms == 1000) {
      EXPECT_TRUE(writer->metadata("session", {{"robot", "puma560"}, {"operator", "test"}}));
    }
    if (ms == 2000) {
      EXPECT_TRUE(writer->attach("robot.urdf", "application/xml", kStart + ms * 1'000'000,
                                 kStart - 5, mcap_bytes(kUrdf)));
      out.attachment_sha256 = core::sha256_hex(kUrdf);
    }
    for (Topic& topic : topics) {
      if (ms % topic.period_ms != 0) continue;
      std::string data;
      if (topic.name == "/camera/left/compressed") {
        data.resize(6000);
        for (char& c : data) c = static_cast<char>(rng());
      } else {
        data = "{\"t\":" + std::to_string(ms) + ",\"q\":[";
        for (int j = 0; j < (topic.name == "/tf" ? 3 : 6); ++j) {
          data += std::to_string(static_cast<double>(rng() % 100000) / 1e4) + ",";
        }
        data += "0]}";
      }
      WrittenMessage m;
      m.topic = topic.name;
      m.sequence = topic.sequence++;
      // Sub-millisecond offsets per topic, so that messages of one millisecond differ in time.
      m.log_time = kStart + ms * 1'000'000 + topic.channel * 1000;
      m.publish_time = m.log_time - 250'000 - m.sequence;
      m.sha256 = core::sha256_hex(data);
      m.chunk = writer->statistics().chunk_count;  // the chunk being filled
      EXPECT_TRUE(
          writer->write(topic.channel, m.sequence, m.log_time, m.publish_time, mcap_bytes(data)));
      out.messages.push_back(m);
    }
  }
  EXPECT_TRUE(writer->close());
  out.statistics = writer->statistics();
  return out;
}

// The sidecar the reader compares each message with.
std::string write_expectations(const test_files::TempDir& dir, const Recording& recording) {
  json messages = json::array();
  for (const WrittenMessage& m : recording.messages) {
    messages.push_back({{"topic", m.topic},
                        {"sequence", m.sequence},
                        {"log_time", std::to_string(m.log_time)},
                        {"publish_time", std::to_string(m.publish_time)},
                        {"sha256", m.sha256}});
  }
  return dir.write("expect.json", json{{"messages", messages}}.dump());
}

// Runs the reference reader on `files`; its JSON report, or null (the test has failed).
json read_with_reference_reader(const std::string& expectations,
                                const std::vector<std::string>& files) {
  const std::string reader_dir = TELEAR_MCAP_READER_DIR;
  if (!std::filesystem::exists(reader_dir + "/node_modules/@mcap/core/package.json")) {
    ADD_FAILURE() << "the reference reader is not installed: run `npm ci --prefix " << reader_dir
                  << "` (scripts/test.sh does)";
    return nullptr;
  }
  std::string command = std::string("'") + TELEAR_NODE_EXECUTABLE + "' '" + reader_dir +
                        "/read_mcap.mjs' --expect '" + expectations + "'";
  for (const std::string& file : files) command += " '" + file + "'";
  std::FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) {
    ADD_FAILURE() << "cannot run " << command;
    return nullptr;
  }
  std::string output;
  char buffer[65536];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof(buffer), pipe)) > 0;) {
    output.append(buffer, n);
  }
  const int status = pclose(pipe);
  if (status != 0) {
    ADD_FAILURE() << command << " failed (status " << status << "):\n" << output;
    return nullptr;
  }
  json report = json::parse(output, nullptr, /*allow_exceptions=*/false);
  if (report.is_discarded()) ADD_FAILURE() << "not JSON:\n" << output;
  return report;
}

struct TopicSummary {
  std::uint64_t count = 0;
  std::string first_log_time;
  std::string last_log_time;
  bool operator==(const TopicSummary&) const = default;
};

std::map<std::string, TopicSummary> summarize(const std::vector<WrittenMessage>& messages) {
  std::map<std::string, TopicSummary> out;
  for (const WrittenMessage& m : messages) {  // log times increase in write order
    TopicSummary& t = out[m.topic];
    if (t.count++ == 0) t.first_log_time = std::to_string(m.log_time);
    t.last_log_time = std::to_string(m.log_time);
  }
  return out;
}

std::map<std::string, TopicSummary> topics_read(const json& reader) {
  std::map<std::string, TopicSummary> out;
  for (const auto& [topic, t] : reader.at("topics").items()) {
    out[topic] = {t.at("count").get<std::uint64_t>(), t.at("first_log_time").get<std::string>(),
                  t.at("last_log_time").get<std::string>()};
  }
  return out;
}

// Every message read matched one written, none twice, none unknown.
void expect_messages_match(const json& reader, const char* which) {
  EXPECT_EQ(reader.at("mismatches"), 0) << which << ": " << reader.at("problems");
  EXPECT_EQ(reader.at("unknown"), 0) << which << ": " << reader.at("problems");
  EXPECT_EQ(reader.at("duplicates"), 0) << which << ": " << reader.at("problems");
}

void expect_reads_whole_recording(const json& file, const Recording& recording,
                                  const std::string& compression) {
  SCOPED_TRACE(file.at("file").get<std::string>());
  const auto expected_topics = summarize(recording.messages);
  const McapStatistics& s = recording.statistics;

  const json& indexed = file.at("indexed");
  ASSERT_FALSE(indexed.contains("error")) << indexed.at("error");
  EXPECT_EQ(indexed.at("header").at("library"), "telear mcap_reference_test");
  EXPECT_EQ(indexed.at("header").at("profile"), "");
  std::set<std::string> schemas;
  for (const json& schema : indexed.at("schemas")) schemas.insert(schema.at("name"));
  EXPECT_EQ(schemas, (std::set<std::string>{"telear.JointStates", "foxglove.CompressedImage"}));
  std::map<std::string, json> channels;
  for (const json& channel : indexed.at("channels")) channels[channel.at("topic")] = channel;
  ASSERT_EQ(channels.size(), 4u);
  EXPECT_EQ(channels["/joint_states"].at("metadata"), (json{{"robot", "puma560"}}));
  EXPECT_EQ(channels["/events"].at("schema_id"), 0);
  EXPECT_EQ(channels["/camera/left/compressed"].at("message_encoding"), "json");

  const json& st = indexed.at("statistics");
  EXPECT_EQ(st.at("message_count"), std::to_string(recording.messages.size()));
  EXPECT_EQ(st.at("schema_count"), 2);
  EXPECT_EQ(st.at("channel_count"), 4);
  EXPECT_EQ(st.at("attachment_count"), 1);
  EXPECT_EQ(st.at("metadata_count"), 1);
  EXPECT_EQ(st.at("chunk_count"), s.chunk_count);
  EXPECT_EQ(st.at("message_start_time"), std::to_string(recording.messages.front().log_time));
  EXPECT_EQ(st.at("message_end_time"), std::to_string(recording.messages.back().log_time));
  for (const auto& [topic, t] : expected_topics) {
    EXPECT_EQ(st.at("channel_message_counts").at(topic), std::to_string(t.count)) << topic;
  }
  EXPECT_GT(s.chunk_count, 8u);
  EXPECT_EQ(indexed.at("chunk_indexes"), s.chunk_count);
  EXPECT_EQ(indexed.at("chunk_compression"), json::array({compression}));
  EXPECT_EQ(indexed.at("data_section_crc_ok"), true);
  EXPECT_EQ(indexed.at("log_time_ordered"), true);
  EXPECT_EQ(indexed.at("messages"), recording.messages.size());
  EXPECT_EQ(topics_read(indexed), expected_topics);
  expect_messages_match(indexed, "indexed");
  ASSERT_EQ(indexed.at("attachments").size(), 1u);
  const json& attachment = indexed.at("attachments")[0];
  EXPECT_EQ(attachment.at("name"), "robot.urdf");
  EXPECT_EQ(attachment.at("media_type"), "application/xml");
  EXPECT_EQ(attachment.at("log_time"), std::to_string(kStart + 2000 * 1'000'000ull));
  EXPECT_EQ(attachment.at("create_time"), std::to_string(kStart - 5));
  EXPECT_EQ(attachment.at("sha256"), recording.attachment_sha256);
  const json metadata = json::array(
      {{{"name", "session"}, {"metadata", {{"operator", "test"}, {"robot", "puma560"}}}}});
  EXPECT_EQ(indexed.at("metadata"), metadata);

  const json& stream = file.at("stream");
  ASSERT_FALSE(stream.contains("error")) << stream.at("error");
  EXPECT_EQ(stream.at("complete"), true);
  EXPECT_EQ(stream.at("bytes_left"), 0);
  EXPECT_EQ(stream.at("data_end"), true);
  EXPECT_EQ(stream.at("chunks"), s.chunk_count);
  EXPECT_EQ(stream.at("messages"), recording.messages.size());
  EXPECT_EQ(topics_read(stream), expected_topics);
  expect_messages_match(stream, "stream");
  EXPECT_EQ(stream.at("attachments"),
            json::array({{{"name", "robot.urdf"}, {"sha256", recording.attachment_sha256}}}));
  EXPECT_EQ(stream.at("metadata"), metadata);
}

TEST(McapReferenceReader, ReadsEveryMessageIndexedAndStreamed) {
  test_files::TempDir dir("mcap_reference");
  const std::string zstd_path = dir.file("session_zstd.mcap");
  const std::string plain_path = dir.file("session_none.mcap");
  Recording zstd = write_session(zstd_path, McapCompression::kZstd);
  Recording plain = write_session(plain_path, McapCompression::kNone);
  ASSERT_FALSE(HasFailure());
  // The same messages either way (the payloads are seeded); zstd shrinks the text ones.
  ASSERT_EQ(zstd.messages.size(), plain.messages.size());
  EXPECT_LT(std::filesystem::file_size(zstd_path), std::filesystem::file_size(plain_path));

  json report = read_with_reference_reader(write_expectations(dir, zstd), {zstd_path, plain_path});
  ASSERT_TRUE(report.is_object());
  ASSERT_EQ(report.at("files").size(), 2u);
  expect_reads_whole_recording(report.at("files")[0], zstd, "zstd");
  expect_reads_whole_recording(report.at("files")[1], plain, "");
}

TEST(McapReferenceReader, ReadsATruncatedFileUpToItsLastCompleteChunk) {
  test_files::TempDir dir("mcap_truncated");
  const std::string path = dir.file("session.mcap");
  Recording recording = write_session(path, McapCompression::kZstd);
  ASSERT_FALSE(HasFailure());
  const auto bytes = mcap_test::read_file(path);

  // Where each chunk record ends, in file order, from the summary's chunk indexes.
  const std::uint64_t footer_at = bytes.size() - 8 - 29;
  mcap_test::FieldReader footer = mcap_test::record_at(bytes, footer_at).fields(bytes);
  const auto summary_start = footer.get<std::uint64_t>();
  const auto summary_offset_start = footer.get<std::uint64_t>();
  std::vector<std::uint64_t> chunk_ends;
  for (const auto& r : mcap_test::records_in(bytes, summary_start, summary_offset_start)) {
    if (r.opcode != 0x08) continue;
    mcap_test::FieldReader index = r.fields(bytes);
    index.get<std::uint64_t>();
    index.get<std::uint64_t>();
    const auto offset = index.get<std::uint64_t>();
    chunk_ends.push_back(offset + index.get<std::uint64_t>());
  }
  std::sort(chunk_ends.begin(), chunk_ends.end());
  ASSERT_EQ(chunk_ends.size(), recording.statistics.chunk_count);
  const std::uint64_t data_end = summary_start - 13;  // the Data End record is 13 bytes

  // Cuts: seeded random ones through the data section, and the edges -- inside the magic, just
  // before and exactly at the end of a chunk, before the Data End record, inside the summary.
  std::mt19937_64 rng(20240522);
  std::uniform_int_distribution<std::uint64_t> anywhere(8, data_end);
  std::vector<std::uint64_t> cuts = {4, chunk_ends[2] - 1, chunk_ends[2], data_end,
                                     bytes.size() - 20};
  for (int i = 0; i < 8; ++i) cuts.push_back(anywhere(rng));
  std::vector<std::string> files;
  for (std::uint64_t cut : cuts) {
    files.push_back(dir.file("cut_" + std::to_string(cut) + ".mcap"));
    std::ofstream(files.back(), std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(cut));
  }

  json report = read_with_reference_reader(write_expectations(dir, recording), files);
  ASSERT_TRUE(report.is_object());
  ASSERT_EQ(report.at("files").size(), cuts.size());
  for (std::size_t i = 0; i < cuts.size(); ++i) {
    const std::uint64_t cut = cuts[i];
    SCOPED_TRACE("cut at byte " + std::to_string(cut) + " of " + std::to_string(bytes.size()));
    std::vector<WrittenMessage> complete;
    for (const WrittenMessage& m : recording.messages) {
      if (chunk_ends[m.chunk] <= cut) complete.push_back(m);
    }
    const json& stream = report.at("files")[i].at("stream");
    EXPECT_FALSE(stream.contains("error")) << stream.at("error");
    EXPECT_EQ(stream.at("complete"), false);
    EXPECT_EQ(stream.at("messages"), complete.size());
    EXPECT_EQ(topics_read(stream), summarize(complete));
    expect_messages_match(stream, "stream");
    // Without its footer the file cannot be read through the index; @mcap/core says so.
    const json& indexed = report.at("files")[i].at("indexed");
    EXPECT_TRUE(indexed.contains("error"));
    if (i == 0 && indexed.contains("error")) {
      std::cout << "McapIndexedReader on a truncated file: " << indexed.at("error") << "\n";
    }
  }
}

}  // namespace
}  // namespace telear::record
