// The MCAP reader against files McapWriter writes: every message back, byte for byte and in
// log-time order across chunks that overlap in time (zstd and uncompressed); the summary's
// schemas, channels, statistics, attachments and metadata; time and topic filters; files cut
// short at many offsets (a recorder killed mid-recording), read up to their last complete chunk;
// and damaged files (wrong magic, garbage, a length past the end, corrupt zstd data, CRC
// mismatches, unknown opcodes), whose errors say what and where.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <map>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "mcap_test_records.hpp"
#include "telear/record/mcap_reader.hpp"
#include "telear/record/mcap_writer.hpp"
#include "test_util/temp_dir.hpp"

namespace telear::record {
// Named rather than anonymous: the test sources are built as one unity source, in which an
// anonymous namespace would merge with the writer tests' (which have a Recording of their own).
namespace mcap_reader_test {

struct Written {
  std::uint16_t channel = 0;
  std::uint32_t sequence = 0;
  std::uint64_t log_time = 0;
  std::uint64_t publish_time = 0;
  std::string data;
  std::uint32_t chunk = 0;  // which chunk of the file (0, 1, ...) holds it
};

bool operator==(const Written& a, const Written& b) {
  return std::tie(a.channel, a.sequence, a.log_time, a.publish_time, a.data) ==
         std::tie(b.channel, b.sequence, b.log_time, b.publish_time, b.data);
}

std::ostream& operator<<(std::ostream& out, const Written& w) {
  return out << "{channel " << w.channel << ", sequence " << w.sequence << ", log " << w.log_time
             << ", publish " << w.publish_time << ", " << w.data.size() << " bytes}";
}

const std::vector<std::string> kTopics = {"/joints", "/camera", "/events"};

struct Recording {
  std::vector<Written> messages;  // in the order written (the file's order)
  McapStatistics statistics;      // the writer's
  std::uint64_t size = 0;
};

// Writes `count` messages on three channels into chunks of about `chunk_size` bytes, with an
// attachment and two metadata records along the way. Log times jitter by up to +-`jitter_ns`
// around a 1 ms step, so consecutive chunks overlap in time and the file is not in log-time
// order; the camera channel's payloads are larger and binary.
Recording write_recording(const std::string& path, McapCompression compression, int count,
                          std::uint64_t chunk_size = 16 * 1024,
                          std::uint64_t jitter_ns = 4'000'000) {
  Recording out;
  McapWriterOptions options;
  options.profile = "telear-test";
  options.library = "mcap_reader_test";
  options.compression = compression;
  options.chunk_size = chunk_size;
  auto writer = McapWriter::open(path, options);
  EXPECT_TRUE(writer.ok()) << writer.error().message;
  if (!writer.ok()) return out;
  const std::uint16_t json = writer->add_schema("telear.Joints", "jsonschema", mcap_bytes("{}"));
  const std::uint16_t blob = writer->add_schema("telear.Frame", "protobuf", mcap_bytes("\x01\x02"));
  writer->add_channel(json, kTopics[0], "json", {{"rate_hz", "500"}});
  writer->add_channel(blob, kTopics[1], "protobuf", {});
  writer->add_channel(0, kTopics[2], "", {{"a", "1"}, {"b", "2"}});

  std::mt19937 rng(42);
  std::uint32_t chunk = 0;
  std::size_t unflushed = 0;  // index of the first message not yet in a written chunk
  std::uint64_t written_bytes = writer->bytes_written();
  for (int i = 0; i < count; ++i) {
    Written w;
    w.channel = static_cast<std::uint16_t>(1 + i % 3);
    w.sequence = static_cast<std::uint32_t>(i);
    const std::uint64_t jitter = jitter_ns == 0 ? 0 : rng() % (2 * jitter_ns);
    w.log_time = 10'000'000'000ull + static_cast<std::uint64_t>(i) * 1'000'000 + jitter;
    w.publish_time = w.log_time - 123;
    if (w.channel == 2) {
      w.data.resize(40 + rng() % 200);
      for (char& c : w.data) c = static_cast<char>(rng());
    } else {
      w.data = "message " + std::to_string(i) + std::string(i % 17, 'x');
    }
    if (i % 500 == 0) w.log_time = 10'000'000'000ull;  // equal log times: file order breaks ties
    EXPECT_TRUE(
        writer->write(w.channel, w.sequence, w.log_time, w.publish_time, mcap_bytes(w.data)));
    out.messages.push_back(w);
    if (writer->bytes_written() != written_bytes) {  // this write completed a chunk
      for (; unflushed < out.messages.size(); ++unflushed) out.messages[unflushed].chunk = chunk;
      ++chunk;
      written_bytes = writer->bytes_written();
    }
    if (i == count / 3) {
      EXPECT_TRUE(writer->attach("robot.urdf", "application/xml", 5, 6,
                                 mcap_bytes("<robot name=\"puma560\"/>")));
      EXPECT_TRUE(writer->metadata("session", {{"robot", "puma560"}, {"operator", "ana"}}));
      written_bytes = writer->bytes_written();
    }
    if (i == 2 * count / 3) {
      EXPECT_TRUE(writer->attach("empty.bin", "application/octet-stream", 7, 8, {}));
      EXPECT_TRUE(writer->metadata("session", {{"note", "second"}}));
      written_bytes = writer->bytes_written();
    }
  }
  for (; unflushed < out.messages.size(); ++unflushed) out.messages[unflushed].chunk = chunk;
  EXPECT_TRUE(writer->close());
  out.statistics = writer->statistics();
  out.size = writer->bytes_written();
  return out;
}

// The messages in the order the reader must give them: by log time, ties in file order.
std::vector<Written> by_log_time(std::vector<Written> messages) {
  std::stable_sort(messages.begin(), messages.end(),
                   [](const Written& a, const Written& b) { return a.log_time < b.log_time; });
  return messages;
}

std::vector<Written> read_all(const McapReader& reader, const McapReadOptions& options = {},
                              Status* status = nullptr) {
  std::vector<Written> out;
  Status read = reader.read_messages(
      [&](const McapMessageView& m) {
        Written w;
        w.channel = m.channel_id;
        w.sequence = m.sequence;
        w.log_time = m.log_time;
        w.publish_time = m.publish_time;
        w.data.assign(reinterpret_cast<const char*>(m.data.data()), m.data.size());
        EXPECT_EQ(m.topic, reader.channels().at(m.channel_id).topic);
        out.push_back(std::move(w));
        return true;
      },
      options);
  if (status) {
    *status = read;
  } else {
    EXPECT_TRUE(read.ok()) << read.error().message;
  }
  return out;
}

void write_bytes(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
}

// The data section's Chunk records (the writer's layout, read by the test-side parser).
std::vector<mcap_test::Record> chunk_records(const std::vector<std::uint8_t>& bytes) {
  std::vector<mcap_test::Record> chunks;
  for (std::uint64_t at = 8; at < bytes.size();) {
    mcap_test::Record r = mcap_test::record_at(bytes, at);
    if (r.opcode == 0x0F) break;  // Data End
    if (r.opcode == 0x06) chunks.push_back(r);
    at = r.end();
  }
  return chunks;
}

std::string error_of(const Result<McapReader>& reader) {
  return reader.ok() ? std::string("(opened)") : reader.error().message;
}

class McapReaderRoundTrip : public ::testing::TestWithParam<McapCompression> {};

TEST_P(McapReaderRoundTrip, ReadsBackEveryMessageInLogTimeOrder) {
  test_files::TempDir dir("mcap_reader");
  const std::string path = dir.file("session.mcap");
  const Recording recording = write_recording(path, GetParam(), 3000);
  ASSERT_GE(recording.statistics.chunk_count, 10u);

  auto reader = McapReader::open(path);
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  EXPECT_TRUE(reader->complete());
  EXPECT_EQ(reader->unread_tail_bytes(), 0u);
  EXPECT_EQ(reader->file_size(), recording.size);
  EXPECT_EQ(reader->profile(), "telear-test");
  EXPECT_EQ(reader->library(), "mcap_reader_test");

  ASSERT_EQ(reader->schemas().size(), 2u);
  const McapSchema& frame = reader->schemas().at(2);
  EXPECT_EQ(frame.id, 2);
  EXPECT_EQ(frame.name, "telear.Frame");
  EXPECT_EQ(frame.encoding, "protobuf");
  EXPECT_EQ(frame.data, (std::vector<std::uint8_t>{1, 2}));
  EXPECT_EQ(reader->schemas().at(1).name, "telear.Joints");
  ASSERT_EQ(reader->channels().size(), 3u);
  for (std::uint16_t id = 1; id <= 3; ++id)
    EXPECT_EQ(reader->channels().at(id).topic, kTopics[id - 1]);
  EXPECT_EQ(reader->channels().at(1).schema_id, 1);
  EXPECT_EQ(reader->channels().at(1).message_encoding, "json");
  EXPECT_EQ(reader->channels().at(1).metadata,
            (std::map<std::string, std::string>{{"rate_hz", "500"}}));
  EXPECT_EQ(reader->channels().at(3).schema_id, 0);
  EXPECT_EQ(reader->channels().at(3).metadata.size(), 2u);

  const McapStatistics& s = reader->statistics();
  const McapStatistics& w = recording.statistics;
  EXPECT_EQ(s.message_count, 3000u);
  EXPECT_EQ(s.schema_count, w.schema_count);
  EXPECT_EQ(s.channel_count, w.channel_count);
  EXPECT_EQ(s.attachment_count, 2u);
  EXPECT_EQ(s.metadata_count, 2u);
  EXPECT_EQ(s.chunk_count, w.chunk_count);
  EXPECT_EQ(s.message_start_time, w.message_start_time);
  EXPECT_EQ(s.message_end_time, w.message_end_time);
  EXPECT_EQ(s.channel_message_counts, w.channel_message_counts);

  const std::vector<Written> read = read_all(*reader);
  const std::vector<Written> expected = by_log_time(recording.messages);
  ASSERT_EQ(read.size(), expected.size());
  EXPECT_NE(expected, recording.messages);  // the jitter did put the file out of log-time order
  for (std::size_t i = 0; i < read.size(); ++i) ASSERT_EQ(read[i], expected[i]) << "message " << i;

  // Reading again gives the same (the reader keeps no state between reads).
  EXPECT_EQ(read_all(*reader).size(), 3000u);
}

INSTANTIATE_TEST_SUITE_P(Compression, McapReaderRoundTrip,
                         ::testing::Values(McapCompression::kZstd, McapCompression::kNone),
                         [](const auto& info) {
                           return info.param == McapCompression::kZstd ? "Zstd" : "None";
                         });

TEST(McapReader, ReadsAttachmentsAndMetadataInFileOrder) {
  test_files::TempDir dir("mcap_reader");
  const std::string path = dir.file("session.mcap");
  write_recording(path, McapCompression::kZstd, 300, 1024);
  auto reader = McapReader::open(path);
  ASSERT_TRUE(reader.ok()) << reader.error().message;

  auto attachments = reader->attachments();
  ASSERT_TRUE(attachments.ok()) << attachments.error().message;
  ASSERT_EQ(attachments->size(), 2u);
  const McapAttachment& urdf = attachments->at(0);
  EXPECT_EQ(urdf.name, "robot.urdf");
  EXPECT_EQ(urdf.media_type, "application/xml");
  EXPECT_EQ(urdf.log_time, 5u);
  EXPECT_EQ(urdf.create_time, 6u);
  EXPECT_EQ(std::string(urdf.data.begin(), urdf.data.end()), "<robot name=\"puma560\"/>");
  EXPECT_EQ(attachments->at(1).name, "empty.bin");
  EXPECT_TRUE(attachments->at(1).data.empty());

  auto metadata = reader->metadata();
  ASSERT_TRUE(metadata.ok()) << metadata.error().message;
  ASSERT_EQ(metadata->size(), 2u);  // both records named "session", kept apart
  EXPECT_EQ(metadata->at(0).name, "session");
  EXPECT_EQ(metadata->at(0).entries,
            (std::map<std::string, std::string>{{"operator", "ana"}, {"robot", "puma560"}}));
  EXPECT_EQ(metadata->at(1).entries, (std::map<std::string, std::string>{{"note", "second"}}));
}

TEST(McapReader, TimeRangeAndTopicFiltersSelectExactlyTheirMessages) {
  test_files::TempDir dir("mcap_reader");
  const std::string path = dir.file("session.mcap");
  const Recording recording = write_recording(path, McapCompression::kZstd, 2000, 4096);
  auto reader = McapReader::open(path);
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  const std::vector<Written> all = by_log_time(recording.messages);

  auto expect_selection = [&](const McapReadOptions& options) {
    std::vector<Written> expected;
    for (const Written& w : all) {
      const std::string& topic = kTopics[w.channel - 1];
      if (w.log_time >= options.start_ns && w.log_time <= options.end_ns &&
          (options.topics.empty() || std::find(options.topics.begin(), options.topics.end(),
                                               topic) != options.topics.end())) {
        expected.push_back(w);
      }
    }
    const std::vector<Written> read = read_all(*reader, options);
    EXPECT_EQ(read, expected) << "range [" << options.start_ns << ", " << options.end_ns << "], "
                              << options.topics.size() << " topics";
    return read.size();
  };

  McapReadOptions range;
  range.start_ns = all[500].log_time;  // both ends are included
  range.end_ns = all[1200].log_time;
  EXPECT_GE(expect_selection(range), 701u);
  McapReadOptions topics;
  topics.topics = {"/camera", "/events"};
  EXPECT_EQ(expect_selection(topics), 2000u * 2 / 3);
  McapReadOptions both = range;
  both.topics = {"/joints"};
  EXPECT_GT(expect_selection(both), 200u);
  McapReadOptions one_instant;
  one_instant.start_ns = one_instant.end_ns = 10'000'000'000ull;  // the tied messages
  EXPECT_EQ(expect_selection(one_instant), 4u);
  McapReadOptions after_end;
  after_end.start_ns = all.back().log_time + 1;
  EXPECT_EQ(expect_selection(after_end), 0u);
  McapReadOptions unknown_topic;
  unknown_topic.topics = {"/nothing"};
  EXPECT_EQ(expect_selection(unknown_topic), 0u);

  // A visitor returning false ends the read, successfully.
  int visits = 0;
  Status stopped = reader->read_messages([&](const McapMessageView&) { return ++visits < 10; });
  EXPECT_TRUE(stopped.ok());
  EXPECT_EQ(visits, 10);
}

TEST(McapReader, ChunkIndexesSkipChunksOutsideTheTimeRange) {
  // Without jitter the chunks are in time order and do not overlap; the first chunk's CRC is
  // then broken, so a read that touched it would fail.
  test_files::TempDir dir("mcap_reader");
  const std::string path = dir.file("session.mcap");
  const Recording recording =
      write_recording(path, McapCompression::kNone, 1000, 2048, /*jitter_ns=*/0);
  auto bytes = mcap_test::read_file(path);
  const auto chunks = chunk_records(bytes);
  ASSERT_GE(chunks.size(), 5u);
  bytes[chunks[0].end() - 1] ^= 0xFF;  // the last byte of the first chunk's last message
  write_bytes(path, bytes);

  auto reader = McapReader::open(path);
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  EXPECT_TRUE(reader->complete());
  // Chunk 0 ends before message 600's log time (the tied messages, whose log times are the
  // first one's, are in later chunks).
  ASSERT_GT(recording.messages[500].chunk, 0u);
  ASSERT_EQ(recording.messages[5].chunk, 0u);
  ASSERT_GT(recording.messages[599].chunk, 0u);
  McapReadOptions later;
  later.start_ns = recording.messages[600].log_time;
  Status status;
  const std::vector<Written> read = read_all(*reader, later, &status);
  EXPECT_TRUE(status.ok()) << status.error().message;
  EXPECT_EQ(read.size(),
            std::count_if(recording.messages.begin(), recording.messages.end(),
                          [&](const Written& w) { return w.log_time >= later.start_ns; }));

  read_all(*reader, {}, &status);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.error().message.find("chunk at offset " + std::to_string(chunks[0].offset) +
                                        ": CRC mismatch: the records' CRC-32 is 0x"),
            std::string::npos)
      << status.error().message;
}

TEST(McapReader, AFileCutShortReadsEveryMessageOfItsCompleteChunks) {
  test_files::TempDir dir("mcap_reader");
  const std::string path = dir.file("session.mcap");
  const Recording recording = write_recording(path, McapCompression::kZstd, 1500, 4096);
  const auto bytes = mcap_test::read_file(path);
  const auto chunks = chunk_records(bytes);
  ASSERT_EQ(chunks.size(), recording.statistics.chunk_count);
  ASSERT_GE(chunks.size(), 6u);

  // Cuts inside the header, at a chunk's end, one byte short of it, inside a chunk, inside the
  // record prefix after a chunk, inside the summary, and short of the closing magic.
  std::vector<std::uint64_t> cuts = {30, chunks[0].offset + 3};
  for (std::size_t k : {std::size_t{0}, std::size_t{2}, chunks.size() - 1}) {
    cuts.push_back(chunks[k].end());
    cuts.push_back(chunks[k].end() - 1);
    cuts.push_back(chunks[k].offset + 40);
    cuts.push_back(chunks[k].end() + 4);
  }
  cuts.push_back(bytes.size() - 100);
  cuts.push_back(bytes.size() - 1);
  cuts.push_back(bytes.size() - 8);

  const std::uint64_t header_end = mcap_test::record_at(bytes, 8).end();
  for (std::uint64_t cut : cuts) {
    SCOPED_TRACE("cut at " + std::to_string(cut) + " of " + std::to_string(bytes.size()));
    const std::string cut_path = dir.file("cut.mcap");
    write_bytes(cut_path, std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + cut));
    auto reader = McapReader::open(cut_path);
    if (cut < header_end) {  // inside the header: nothing to read
      ASSERT_FALSE(reader.ok());
      EXPECT_EQ(reader.error().message, "McapReader: '" + cut_path +
                                            "': the file ends inside its Header record at "
                                            "offset 8 (" +
                                            std::to_string(cut) + " bytes in all)");
      continue;
    }
    ASSERT_TRUE(reader.ok()) << reader.error().message;
    EXPECT_FALSE(reader->complete());
    const auto complete_chunks = static_cast<std::uint32_t>(std::count_if(
        chunks.begin(), chunks.end(), [&](const mcap_test::Record& c) { return c.end() <= cut; }));
    std::vector<Written> expected;
    for (const Written& w : recording.messages) {
      if (w.chunk < complete_chunks) expected.push_back(w);
    }
    expected = by_log_time(expected);
    EXPECT_EQ(reader->statistics().chunk_count, complete_chunks);
    EXPECT_EQ(reader->statistics().message_count, expected.size());
    EXPECT_EQ(reader->channels().size(), 3u);  // written before the first chunk
    EXPECT_EQ(read_all(*reader), expected);
    if (!expected.empty()) {
      EXPECT_EQ(reader->statistics().message_start_time, expected.front().log_time);
      EXPECT_EQ(reader->statistics().message_end_time, expected.back().log_time);
    }
    if (cut == chunks[2].end()) {
      EXPECT_EQ(reader->unread_tail_bytes(), 0u);
    }
    if (cut == chunks[2].end() - 1) {
      EXPECT_EQ(reader->unread_tail_bytes(), chunks[2].end() - 1 - chunks[2].offset);
    }
    if (cut >= bytes.size() - 100) {  // past Data End: every message, attachment and metadata
      EXPECT_EQ(reader->statistics().message_count, 1500u);
      EXPECT_EQ(reader->statistics().attachment_count, 2u);
      auto metadata = reader->metadata();
      ASSERT_TRUE(metadata.ok()) << metadata.error().message;
      EXPECT_EQ(metadata->size(), 2u);
    }
  }
}

TEST(McapReader, RefusesFilesThatAreNotMcap) {
  test_files::TempDir dir("mcap_reader");
  const std::string missing = dir.file("missing.mcap");
  auto none = McapReader::open(missing);
  EXPECT_EQ(error_of(none),
            "McapReader: '" + missing + "': cannot open: No such file or directory");

  const std::string empty = dir.write("empty.mcap", "");
  EXPECT_EQ(
      error_of(McapReader::open(empty)),
      "not an MCAP file: '" + empty + "' is 0 bytes long, shorter than the 8-byte MCAP magic");

  const std::string text = dir.write("notes.txt", "just some text, long enough to be read");
  EXPECT_EQ(error_of(McapReader::open(text)),
            "not an MCAP file: '" + text + "' does not start with the MCAP magic");

  // The magic, then garbage where the Header record belongs.
  std::string garbage("\x89MCAP0\r\n", 8);
  garbage += std::string("\x42\x05\x00\x00\x00\x00\x00\x00\x00hello", 14);
  const std::string bad_header = dir.write("garbage.mcap", garbage);
  EXPECT_EQ(error_of(McapReader::open(bad_header)),
            "McapReader: '" + bad_header +
                "': expected the Header record (opcode 0x01) at offset 8, found opcode 0x42");

  EXPECT_EQ(error_of(McapReader::open(dir.string())),
            "McapReader: '" + dir.string() + "': not a regular file");
}

TEST(McapReader, ReportsARecordLengthBeyondTheFile) {
  test_files::TempDir dir("mcap_reader");
  const std::string path = dir.file("session.mcap");
  write_recording(path, McapCompression::kZstd, 400, 2048);
  auto bytes = mcap_test::read_file(path);
  const auto chunks = chunk_records(bytes);
  ASSERT_GE(chunks.size(), 3u);
  const std::uint64_t huge = 1ull << 40;
  std::memcpy(bytes.data() + chunks[1].offset + 1, &huge, 8);
  write_bytes(path, bytes);

  // The summary is intact, so open() succeeds; reading the chunk fails, naming it.
  auto reader = McapReader::open(path);
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  Status status;
  read_all(*reader, {}, &status);
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.error().message,
            "McapReader: '" + path + "': record at offset " + std::to_string(chunks[1].offset) +
                " (opcode 0x06) has length 1099511627776, beyond the " +
                std::to_string(bytes.size() - chunks[1].offset - 9) + " bytes left before offset " +
                std::to_string(bytes.size()));
}

TEST(McapReader, ReportsCorruptZstdDataNamingTheChunk) {
  test_files::TempDir dir("mcap_reader");
  const std::string path = dir.file("session.mcap");
  write_recording(path, McapCompression::kZstd, 400, 2048);
  auto bytes = mcap_test::read_file(path);
  const auto chunks = chunk_records(bytes);
  ASSERT_GE(chunks.size(), 3u);
  // The chunk's records start after its times, sizes, CRC, "zstd" and records length.
  const std::uint64_t records = chunks[1].content_offset + 8 + 8 + 8 + 4 + 4 + 4 + 8;
  ASSERT_EQ(std::string(bytes.begin() + records - 12, bytes.begin() + records - 8), "zstd");
  std::memset(bytes.data() + records, 0xEE, 4);  // zstd's frame magic
  write_bytes(path, bytes);

  auto reader = McapReader::open(path);
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  Status status;
  const auto read = read_all(*reader, {}, &status);
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.error().message, "McapReader: '" + path + "': chunk at offset " +
                                        std::to_string(chunks[1].offset) +
                                        ": corrupt zstd data: Unknown frame descriptor");

  // A file cut short is scanned at open(), which meets the same chunk.
  const std::string cut = dir.file("cut.mcap");
  write_bytes(cut, std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + chunks[2].end()));
  EXPECT_EQ(error_of(McapReader::open(cut)), "McapReader: '" + cut + "': chunk at offset " +
                                                 std::to_string(chunks[1].offset) +
                                                 ": corrupt zstd data: Unknown frame descriptor");
}

TEST(McapReader, ReportsSummaryAndAttachmentCrcMismatches) {
  test_files::TempDir dir("mcap_reader");
  const std::string path = dir.file("session.mcap");
  write_recording(path, McapCompression::kZstd, 300, 2048);
  const auto bytes = mcap_test::read_file(path);

  // The attachment's data, found by its text, changed by one byte.
  const std::string urdf = "<robot name=\"puma560\"/>";
  auto at = std::search(bytes.begin(), bytes.end(), urdf.begin(), urdf.end());
  ASSERT_NE(at, bytes.end());
  auto damaged = bytes;
  damaged[static_cast<std::size_t>(at - bytes.begin()) + 1] = 'R';
  write_bytes(path, damaged);
  auto reader = McapReader::open(path);
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  auto attachments = reader->attachments();
  ASSERT_FALSE(attachments.ok());
  EXPECT_NE(attachments.error().message.find("': attachment 'robot.urdf' at offset "),
            std::string::npos)
      << attachments.error().message;
  EXPECT_NE(attachments.error().message.find(": CRC mismatch: its CRC-32 is 0x"), std::string::npos)
      << attachments.error().message;

  // A byte of the summary (the first schema's name, in its copy there).
  std::uint64_t summary_start = 0;
  std::memcpy(&summary_start, bytes.data() + bytes.size() - 8 - 20, 8);
  damaged = bytes;
  damaged[summary_start + 9 + 2 + 4] ^= 0x20;
  write_bytes(path, damaged);
  const std::string prefix = "McapReader: '" + path + "': summary at offset " +
                             std::to_string(summary_start) + ": CRC mismatch: its CRC-32 is 0x";
  EXPECT_EQ(error_of(McapReader::open(path)).rfind(prefix, 0), 0u)
      << error_of(McapReader::open(path));
}

TEST(McapReader, SkipsRecordsWithUnknownOpcodes) {
  // A cut file (scanned from the start) with a record of an opcode from the user range after
  // its header: the scan steps over it.
  test_files::TempDir dir("mcap_reader");
  const std::string path = dir.file("session.mcap");
  const Recording recording = write_recording(path, McapCompression::kNone, 200, 1024);
  auto bytes = mcap_test::read_file(path);
  const auto chunks = chunk_records(bytes);
  ASSERT_GE(chunks.size(), 3u);
  bytes.resize(chunks[2].end());
  const mcap_test::Record header = mcap_test::record_at(bytes, 8);
  std::vector<std::uint8_t> unknown = {0x80, 3, 0, 0, 0, 0, 0, 0, 0, 'a', 'b', 'c'};
  bytes.insert(bytes.begin() + static_cast<std::ptrdiff_t>(header.end()), unknown.begin(),
               unknown.end());
  write_bytes(path, bytes);

  auto reader = McapReader::open(path);
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  EXPECT_FALSE(reader->complete());
  std::vector<Written> expected;
  for (const Written& w : recording.messages) {
    if (w.chunk < 3) expected.push_back(w);
  }
  EXPECT_EQ(read_all(*reader), by_log_time(expected));
}

TEST(McapReader, RandomDamageIsAnErrorOrAReadNeverACrash) {
  // Cuts and flipped bytes anywhere in a small file: open() and every read either succeed or
  // return an error of the reader's own (an ASan build of this loop ran 40,000 such files).
  test_files::TempDir dir("mcap_reader");
  const std::string path = dir.file("session.mcap");
  write_recording(path, McapCompression::kZstd, 300, 1024);
  const auto bytes = mcap_test::read_file(path);
  const std::string damaged_path = dir.file("damaged.mcap");
  auto expect_reader_error = [&](const std::string& message) {
    EXPECT_TRUE(message.rfind("McapReader: '" + damaged_path + "': ", 0) == 0 ||
                message.rfind("not an MCAP file: '" + damaged_path + "'", 0) == 0)
        << message;
  };
  std::mt19937 rng(3);
  for (int i = 0; i < 300; ++i) {
    std::vector<std::uint8_t> damaged = bytes;
    if (i % 2 == 0) {
      damaged.resize(rng() % bytes.size());
    } else {
      damaged[rng() % damaged.size()] ^= static_cast<std::uint8_t>(1u << (rng() % 8));
    }
    write_bytes(damaged_path, damaged);
    auto reader = McapReader::open(damaged_path);
    if (!reader.ok()) {
      expect_reader_error(reader.error().message);
      continue;
    }
    Status read = reader->read_messages([](const McapMessageView&) { return true; });
    if (!read.ok()) expect_reader_error(read.error().message);
    if (auto attachments = reader->attachments(); !attachments.ok()) {
      expect_reader_error(attachments.error().message);
    }
    if (auto metadata = reader->metadata(); !metadata.ok()) {
      expect_reader_error(metadata.error().message);
    }
  }
}

}  // namespace mcap_reader_test
}  // namespace telear::record
