// The MCAP writer against the specification, byte by byte (tests/record/mcap_test_records.hpp
// reads the file independently of the writer): magic at both ends, the header, the data section
// (schemas and channels before the chunks, each chunk followed by its message indexes, data end
// with the data section's CRC), the summary grouped by opcode and located by the summary offsets
// and the footer; the statistics; the error paths and their messages. The reference reader's
// view of the same files is tests/record/mcap_reference_test.cpp.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "mcap_test_records.hpp"
#include "telear/core/crc32.hpp"
#include "telear/record/mcap_writer.hpp"
#include "test_util/temp_dir.hpp"

namespace telear::record {
namespace {

using mcap_test::FieldReader;
using mcap_test::Record;
using mcap_test::record_at;
using mcap_test::records_in;

// The CRC of a byte range of the file.
std::uint32_t crc_of(const std::vector<std::uint8_t>& bytes, std::uint64_t begin,
                     std::uint64_t end) {
  return core::crc32(bytes.data() + begin, end - begin);
}

// What check_layout() found in a file, for the tests' own assertions.
struct Layout {
  std::string profile;
  std::string library;
  std::vector<std::uint8_t> data_opcodes;               // the data section's records, in order
  std::map<std::uint8_t, std::vector<Record>> summary;  // summary records by group opcode
  std::uint64_t summary_start = 0;
};

// Checks every structural rule of the spec the writer has to follow and returns the parts.
Layout check_layout(const std::vector<std::uint8_t>& bytes) {
  Layout out;
  constexpr std::uint64_t kFooterRecord = 1 + 8 + 8 + 8 + 4;
  EXPECT_GE(bytes.size(), 8 + 9 + 9 + kFooterRecord + 8);
  if (bytes.size() < 8 + kFooterRecord + 8) return out;
  EXPECT_TRUE(std::equal(mcap_test::kMagic, mcap_test::kMagic + 8, bytes.begin()));
  EXPECT_TRUE(std::equal(mcap_test::kMagic, mcap_test::kMagic + 8, bytes.end() - 8));

  Record header = record_at(bytes, 8);
  EXPECT_EQ(header.opcode, 0x01);
  FieldReader h = header.fields(bytes);
  out.profile = h.string();
  out.library = h.string();
  EXPECT_EQ(h.left(), 0u);

  // The footer: the last record, its fields pointing at the summary and the summary offsets.
  const std::uint64_t footer_at = bytes.size() - 8 - kFooterRecord;
  Record footer = record_at(bytes, footer_at);
  EXPECT_EQ(footer.opcode, 0x02);
  EXPECT_EQ(footer.length, 20u);
  FieldReader f = footer.fields(bytes);
  const auto summary_start = f.get<std::uint64_t>();
  const auto summary_offset_start = f.get<std::uint64_t>();
  const auto summary_crc = f.get<std::uint32_t>();
  out.summary_start = summary_start;
  EXPECT_GT(summary_start, 0u);
  EXPECT_GT(summary_offset_start, summary_start);
  EXPECT_LT(summary_offset_start, footer_at);
  // From the summary's first byte through the footer's summary_offset_start field.
  EXPECT_EQ(summary_crc, crc_of(bytes, summary_start, footer_at + 9 + 16));

  // The data section: records from the header to Data End, which ends where the summary starts.
  std::uint64_t at = header.end();
  std::set<std::uint16_t> schemas_seen;
  std::set<std::uint16_t> channels_seen;
  for (;;) {
    Record r = record_at(bytes, at);
    out.data_opcodes.push_back(r.opcode);
    if (r.opcode == 0x03) schemas_seen.insert(r.fields(bytes).get<std::uint16_t>());
    if (r.opcode == 0x04) {
      FieldReader c = r.fields(bytes);
      channels_seen.insert(c.get<std::uint16_t>());
      const auto schema = c.get<std::uint16_t>();
      EXPECT_TRUE(schema == 0 || schemas_seen.count(schema)) << "channel before its schema";
    }
    if (r.opcode == 0x0F) {  // Data End: the CRC of every byte before it
      EXPECT_EQ(r.length, 4u);
      EXPECT_EQ(r.fields(bytes).get<std::uint32_t>(), crc_of(bytes, 0, r.offset));
      EXPECT_EQ(r.end(), summary_start);
      break;
    }
    EXPECT_TRUE(r.opcode == 0x03 || r.opcode == 0x04 || r.opcode == 0x06 || r.opcode == 0x07 ||
                r.opcode == 0x09 || r.opcode == 0x0C)
        << "opcode " << int(r.opcode) << " in the data section at " << r.offset;
    if (r.end() >= summary_start) {
      ADD_FAILURE() << "no Data End record before the summary";
      return out;
    }
    at = r.end();
  }

  // Summary offsets: one per group; the groups tile the summary section exactly, each holding
  // only records of its opcode, and there is one group per opcode.
  std::uint64_t expected_group_start = summary_start;
  for (const Record& offset : records_in(bytes, summary_offset_start, footer_at)) {
    EXPECT_EQ(offset.opcode, 0x0E);
    FieldReader o = offset.fields(bytes);
    const auto opcode = o.get<std::uint8_t>();
    const auto group_start = o.get<std::uint64_t>();
    const auto group_length = o.get<std::uint64_t>();
    EXPECT_EQ(group_start, expected_group_start) << "group " << int(opcode);
    expected_group_start = group_start + group_length;
    EXPECT_EQ(out.summary.count(opcode), 0u) << "two groups of opcode " << int(opcode);
    for (const Record& r : records_in(bytes, group_start, group_start + group_length)) {
      EXPECT_EQ(r.opcode, opcode) << "in the group of opcode " << int(opcode);
      out.summary[opcode].push_back(r);
    }
  }
  EXPECT_EQ(expected_group_start, summary_offset_start);
  // Channels must precede the Statistics record (its channel_message_counts refers to them).
  if (out.summary.count(0x04) && out.summary.count(0x0B)) {
    EXPECT_LT(out.summary[0x04].back().offset, out.summary[0x0B].front().offset);
  }
  return out;
}

struct ParsedStatistics {
  std::uint64_t message_count = 0;
  std::uint16_t schema_count = 0;
  std::uint32_t channel_count = 0, attachment_count = 0, metadata_count = 0, chunk_count = 0;
  std::uint64_t message_start_time = 0, message_end_time = 0;
  std::map<std::uint16_t, std::uint64_t> channel_message_counts;
};

ParsedStatistics parse_statistics(const std::vector<std::uint8_t>& bytes, const Record& r) {
  ParsedStatistics s;
  FieldReader f = r.fields(bytes);
  s.message_count = f.get<std::uint64_t>();
  s.schema_count = f.get<std::uint16_t>();
  s.channel_count = f.get<std::uint32_t>();
  s.attachment_count = f.get<std::uint32_t>();
  s.metadata_count = f.get<std::uint32_t>();
  s.chunk_count = f.get<std::uint32_t>();
  s.message_start_time = f.get<std::uint64_t>();
  s.message_end_time = f.get<std::uint64_t>();
  const auto map_length = f.get<std::uint32_t>();
  EXPECT_EQ(map_length % 10, 0u);
  for (std::uint32_t i = 0; i < map_length / 10; ++i) {
    const auto channel = f.get<std::uint16_t>();
    s.channel_message_counts[channel] = f.get<std::uint64_t>();
  }
  EXPECT_EQ(f.left(), 0u);
  return s;
}

std::string payload(std::uint16_t channel, std::uint32_t sequence) {
  return "channel " + std::to_string(channel) + " message " + std::to_string(sequence) +
         std::string(sequence % 50, 'x');
}

TEST(McapWriter, FileLayoutFollowsTheSpecification) {
  test_files::TempDir dir("mcap_layout");
  const std::string path = dir.file("layout.mcap");
  McapWriterOptions options;
  options.profile = "telear-test";
  options.library = "telear mcap_writer_test";
  options.compression = McapCompression::kNone;  // the chunks' records are read back below
  options.chunk_size = 600;                      // several chunks
  auto writer = McapWriter::open(path, options);
  ASSERT_TRUE(writer.ok()) << writer.error().message;
  const std::uint16_t schema = writer->add_schema("test.Joints", "jsonschema", mcap_bytes("{}"));
  const std::uint16_t joints = writer->add_channel(schema, "/joints", "json", {{"rate", "500"}});
  const std::uint16_t raw = writer->add_channel(0, "/raw", "", {});
  ASSERT_EQ(schema, 1);
  ASSERT_EQ(joints, 1);
  ASSERT_EQ(raw, 2);
  std::map<std::uint64_t, std::pair<std::uint16_t, std::string>> written;  // by log time
  for (std::uint32_t i = 0; i < 40; ++i) {
    const std::uint16_t channel = (i % 3 == 0) ? raw : joints;
    const std::uint64_t log_time = 1'000'000'000ull + i * 1000;
    ASSERT_TRUE(writer->write(channel, i, log_time, log_time - 7, mcap_bytes(payload(channel, i))));
    written[log_time] = {channel, payload(channel, i)};
    if (i == 20) {
      ASSERT_TRUE(writer->attach("robot.urdf", "application/xml", log_time, 42,
                                 mcap_bytes("<robot name=\"r\"/>")));
      ASSERT_TRUE(writer->metadata("session", {{"robot", "puma560"}, {"operator", "a"}}));
    }
  }
  ASSERT_TRUE(writer->close());
  const std::uint32_t chunks = writer->statistics().chunk_count;
  EXPECT_GE(chunks, 3u);

  const auto bytes = mcap_test::read_file(path);
  ASSERT_EQ(writer->bytes_written(), bytes.size());
  Layout layout = check_layout(bytes);
  ASSERT_FALSE(HasFailure());
  EXPECT_EQ(layout.profile, "telear-test");
  EXPECT_EQ(layout.library, "telear mcap_writer_test");
  // Schema and channels first, then chunks each followed by its message indexes; the
  // attachment and the metadata between chunks; Data End last.
  ASSERT_GE(layout.data_opcodes.size(), 4u);
  EXPECT_EQ(layout.data_opcodes[0], 0x03);
  EXPECT_EQ(layout.data_opcodes[1], 0x04);
  EXPECT_EQ(layout.data_opcodes[2], 0x04);
  EXPECT_EQ(layout.data_opcodes[3], 0x06);
  EXPECT_EQ(std::count(layout.data_opcodes.begin(), layout.data_opcodes.end(), 0x06), chunks);
  EXPECT_EQ(std::count(layout.data_opcodes.begin(), layout.data_opcodes.end(), 0x09), 1);
  EXPECT_EQ(std::count(layout.data_opcodes.begin(), layout.data_opcodes.end(), 0x0C), 1);
  for (std::size_t i = 0; i + 1 < layout.data_opcodes.size(); ++i) {
    if (layout.data_opcodes[i] == 0x06) {
      EXPECT_EQ(layout.data_opcodes[i + 1], 0x07);
    }
  }

  // Summary: a copy of the schema and the channels, the statistics, one chunk index per chunk,
  // the attachment and metadata indexes.
  EXPECT_EQ(layout.summary[0x03].size(), 1u);
  EXPECT_EQ(layout.summary[0x04].size(), 2u);
  EXPECT_EQ(layout.summary[0x0B].size(), 1u);
  EXPECT_EQ(layout.summary[0x08].size(), chunks);
  EXPECT_EQ(layout.summary[0x0A].size(), 1u);
  EXPECT_EQ(layout.summary[0x0D].size(), 1u);
  // The summary's channel record is the data section's, byte for byte.
  const Record& summary_channel = layout.summary[0x04][0];
  Record data_schema = record_at(bytes, record_at(bytes, 8).end());
  Record data_channel = record_at(bytes, data_schema.end());
  ASSERT_EQ(data_channel.opcode, 0x04);
  EXPECT_TRUE(std::equal(bytes.begin() + summary_channel.offset,
                         bytes.begin() + summary_channel.end(), bytes.begin() + data_channel.offset,
                         bytes.begin() + data_channel.end()));

  // Every chunk index leads to its chunk, whose records are the messages written, each where
  // its message index says, with the chunk's CRC and time range.
  std::uint64_t messages_found = 0;
  for (const Record& index : layout.summary[0x08]) {
    FieldReader ci = index.fields(bytes);
    const auto start_time = ci.get<std::uint64_t>();
    const auto end_time = ci.get<std::uint64_t>();
    const auto chunk_offset = ci.get<std::uint64_t>();
    const auto chunk_length = ci.get<std::uint64_t>();
    std::map<std::uint16_t, std::uint64_t> index_offsets;
    const auto map_length = ci.get<std::uint32_t>();
    for (std::uint32_t i = 0; i < map_length / 10; ++i) {
      const auto channel = ci.get<std::uint16_t>();
      index_offsets[channel] = ci.get<std::uint64_t>();
    }
    const auto message_index_length = ci.get<std::uint64_t>();
    EXPECT_EQ(ci.string(), "");
    const auto compressed_size = ci.get<std::uint64_t>();
    const auto uncompressed_size = ci.get<std::uint64_t>();
    EXPECT_EQ(ci.left(), 0u);

    Record chunk = record_at(bytes, chunk_offset);
    ASSERT_EQ(chunk.opcode, 0x06);
    EXPECT_EQ(chunk.end() - chunk.offset, chunk_length);
    FieldReader c = chunk.fields(bytes);
    EXPECT_EQ(c.get<std::uint64_t>(), start_time);
    EXPECT_EQ(c.get<std::uint64_t>(), end_time);
    EXPECT_EQ(c.get<std::uint64_t>(), uncompressed_size);
    const auto crc = c.get<std::uint32_t>();
    EXPECT_EQ(c.string(), "");
    const auto records_length = c.get<std::uint64_t>();
    EXPECT_EQ(records_length, compressed_size);
    EXPECT_EQ(records_length, uncompressed_size);  // no compression
    const std::uint64_t records_at = c.at();
    EXPECT_EQ(records_at + records_length, chunk.end());
    EXPECT_EQ(crc, crc_of(bytes, records_at, records_at + records_length));

    std::uint64_t min_time = ~0ull, max_time = 0;
    for (const Record& m : records_in(bytes, records_at, records_at + records_length)) {
      ASSERT_EQ(m.opcode, 0x05);
      FieldReader mf = m.fields(bytes);
      const auto channel = mf.get<std::uint16_t>();
      mf.get<std::uint32_t>();  // sequence
      const auto log_time = mf.get<std::uint64_t>();
      EXPECT_EQ(mf.get<std::uint64_t>(), log_time - 7);
      ASSERT_EQ(written.count(log_time), 1u);
      EXPECT_EQ(written[log_time].first, channel);
      EXPECT_EQ(mf.bytes(mf.left()), written[log_time].second);
      min_time = std::min(min_time, log_time);
      max_time = std::max(max_time, log_time);
      ++messages_found;
    }
    EXPECT_EQ(min_time, start_time);
    EXPECT_EQ(max_time, end_time);

    // The message indexes: right after the chunk, one per channel in it, entries pointing at
    // that channel's messages (offsets relative to the chunk's uncompressed records).
    EXPECT_EQ(index_offsets.begin()->second, chunk.end());
    std::uint64_t indexes_length = 0;
    for (const auto& [channel, offset] : index_offsets) {
      Record mi = record_at(bytes, offset);
      ASSERT_EQ(mi.opcode, 0x07);
      indexes_length += 9 + mi.length;
      FieldReader mif = mi.fields(bytes);
      EXPECT_EQ(mif.get<std::uint16_t>(), channel);
      const auto entries = mif.get<std::uint32_t>() / 16;
      for (std::uint32_t e = 0; e < entries; ++e) {
        const auto log_time = mif.get<std::uint64_t>();
        const auto message_offset = mif.get<std::uint64_t>();
        Record m = record_at(bytes, records_at + message_offset);
        ASSERT_EQ(m.opcode, 0x05);
        FieldReader mf = m.fields(bytes);
        EXPECT_EQ(mf.get<std::uint16_t>(), channel);
        mf.get<std::uint32_t>();
        EXPECT_EQ(mf.get<std::uint64_t>(), log_time);
      }
    }
    EXPECT_EQ(indexes_length, message_index_length);
  }
  EXPECT_EQ(messages_found, written.size());

  // The attachment: its index points at it, its CRC covers the fields before the CRC.
  FieldReader ai = layout.summary[0x0A][0].fields(bytes);
  const auto attachment_offset = ai.get<std::uint64_t>();
  const auto attachment_length = ai.get<std::uint64_t>();
  ai.get<std::uint64_t>();
  EXPECT_EQ(ai.get<std::uint64_t>(), 42u);  // create time
  EXPECT_EQ(ai.get<std::uint64_t>(), 17u);  // data size
  EXPECT_EQ(ai.string(), "robot.urdf");
  EXPECT_EQ(ai.string(), "application/xml");
  Record attachment = record_at(bytes, attachment_offset);
  ASSERT_EQ(attachment.opcode, 0x09);
  EXPECT_EQ(attachment.end() - attachment.offset, attachment_length);
  FieldReader a(bytes, attachment.end() - 4, attachment.end());
  EXPECT_EQ(a.get<std::uint32_t>(), crc_of(bytes, attachment.content_offset, attachment.end() - 4));

  FieldReader mdi = layout.summary[0x0D][0].fields(bytes);
  Record metadata = record_at(bytes, mdi.get<std::uint64_t>());
  ASSERT_EQ(metadata.opcode, 0x0C);
  EXPECT_EQ(metadata.end() - metadata.offset, mdi.get<std::uint64_t>());
  EXPECT_EQ(mdi.string(), "session");
  FieldReader md = metadata.fields(bytes);
  EXPECT_EQ(md.string(), "session");
  md.get<std::uint32_t>();  // the map's byte length; std::map orders the keys
  EXPECT_EQ(md.string(), "operator");
  EXPECT_EQ(md.string(), "a");
  EXPECT_EQ(md.string(), "robot");
  EXPECT_EQ(md.string(), "puma560");
}

TEST(McapWriter, StatisticsCountWhatWasWritten) {
  test_files::TempDir dir("mcap_statistics");
  const std::string path = dir.file("statistics.mcap");
  McapWriterOptions options;
  options.chunk_size = 4096;
  auto writer = McapWriter::open(path, options);
  ASSERT_TRUE(writer.ok()) << writer.error().message;
  const std::uint16_t schema_a = writer->add_schema("a", "protobuf", mcap_bytes("descriptor a"));
  const std::uint16_t schema_b = writer->add_schema("b", "protobuf", mcap_bytes("descriptor b"));
  const std::uint16_t a = writer->add_channel(schema_a, "/a", "protobuf");
  const std::uint16_t b = writer->add_channel(schema_b, "/b", "protobuf");
  const std::uint16_t silent = writer->add_channel(schema_b, "/silent", "protobuf");
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<std::uint64_t> time(5'000, 9'000'000);
  std::uint64_t earliest = ~0ull, latest = 0;
  for (std::uint32_t i = 0; i < 1500; ++i) {
    const std::uint64_t t = time(rng);  // out of order: the range is a min and a max
    earliest = std::min(earliest, t);
    latest = std::max(latest, t);
    ASSERT_TRUE(writer->write(i % 3 == 0 ? b : a, i, t, t, mcap_bytes(payload(a, i))));
  }
  ASSERT_TRUE(writer->attach("one", "text/plain", 1, 0, mcap_bytes("1")));
  ASSERT_TRUE(writer->attach("two", "text/plain", 2, 0, mcap_bytes("2")));
  ASSERT_TRUE(writer->metadata("m", {}));
  ASSERT_TRUE(writer->close());

  const McapStatistics& s = writer->statistics();
  EXPECT_EQ(s.message_count, 1500u);
  EXPECT_EQ(s.schema_count, 2);
  EXPECT_EQ(s.channel_count, 3u);
  EXPECT_EQ(s.attachment_count, 2u);
  EXPECT_EQ(s.metadata_count, 1u);
  EXPECT_GE(s.chunk_count, 2u);
  EXPECT_EQ(s.message_start_time, earliest);
  EXPECT_EQ(s.message_end_time, latest);
  const std::map<std::uint16_t, std::uint64_t> counts{{a, 1000}, {b, 500}, {silent, 0}};
  EXPECT_EQ(s.channel_message_counts, counts);

  const auto bytes = mcap_test::read_file(path);
  Layout layout = check_layout(bytes);
  ASSERT_EQ(layout.summary[0x0B].size(), 1u);
  ParsedStatistics p = parse_statistics(bytes, layout.summary[0x0B][0]);
  EXPECT_EQ(p.message_count, 1500u);
  EXPECT_EQ(p.schema_count, 2);
  EXPECT_EQ(p.channel_count, 3u);
  EXPECT_EQ(p.attachment_count, 2u);
  EXPECT_EQ(p.metadata_count, 1u);
  EXPECT_EQ(p.chunk_count, s.chunk_count);
  EXPECT_EQ(p.chunk_count, layout.summary[0x08].size());
  EXPECT_EQ(p.message_start_time, earliest);
  EXPECT_EQ(p.message_end_time, latest);
  EXPECT_EQ(p.channel_message_counts, counts);
}

TEST(McapWriter, AnEmptyRecordingIsAValidFile) {
  test_files::TempDir dir("mcap_empty");
  const std::string path = dir.file("empty.mcap");
  {
    auto writer = McapWriter::open(path);
    ASSERT_TRUE(writer.ok()) << writer.error().message;
    // Not closed: the destructor closes it.
  }
  const auto bytes = mcap_test::read_file(path);
  Layout layout = check_layout(bytes);
  EXPECT_EQ(layout.library, "telear");
  EXPECT_EQ(layout.data_opcodes, std::vector<std::uint8_t>{0x0F});
  ASSERT_EQ(layout.summary.size(), 1u);  // the statistics alone
  ParsedStatistics p = parse_statistics(bytes, layout.summary[0x0B].at(0));
  EXPECT_EQ(p.message_count, 0u);
  EXPECT_EQ(p.message_start_time, 0u);
  EXPECT_EQ(p.chunk_count, 0u);
}

TEST(McapWriter, OpenReportsAPathItCannotCreate) {
  test_files::TempDir dir("mcap_open");
  const std::string path = (dir.path() / "no/such/folder/x.mcap").string();
  auto writer = McapWriter::open(path);
  ASSERT_FALSE(writer.ok());
  EXPECT_EQ(writer.error().message,
            "McapWriter::open(): cannot create '" + path + "': No such file or directory");
}

TEST(McapWriter, OpenRejectsInvalidOptionsNamingTheField) {
  test_files::TempDir dir("mcap_options");
  McapWriterOptions options;
  options.zstd_level = 99;
  auto writer = McapWriter::open(dir.file("x.mcap"), options);
  ASSERT_FALSE(writer.ok());
  EXPECT_EQ(
      writer.error().message.rfind(
          "McapWriter::open(): McapWriterOptions: zstd_level 99 is outside zstd's range [", 0),
      0u)
      << writer.error().message;
  EXPECT_FALSE(std::filesystem::exists(dir.file("x.mcap")));  // refused before creating it

  options = {};
  options.chunk_size = 0;
  std::string error;
  EXPECT_FALSE(options.is_valid(&error));
  EXPECT_EQ(error, "McapWriterOptions: chunk_size must be positive");
  options.compression = McapCompression::kNone;
  options.chunk_size = 1;
  options.zstd_level = 99;  // unused without compression
  EXPECT_TRUE(options.is_valid());
}

TEST(McapWriter, WriteRefusesAChannelItNeverAdded) {
  test_files::TempDir dir("mcap_channel");
  auto writer = McapWriter::open(dir.file("x.mcap"));
  ASSERT_TRUE(writer.ok()) << writer.error().message;
  Status none = writer->write(1, 0, 0, 0, mcap_bytes("x"));
  ASSERT_FALSE(none.ok());
  EXPECT_EQ(none.error().message,
            "McapWriter::write(): unknown channel id 1 (no channel was added)");
  writer->add_channel(0, "/a", "json");
  writer->add_channel(0, "/b", "json");
  Status unknown = writer->write(7, 0, 0, 0, mcap_bytes("x"));
  ASSERT_FALSE(unknown.ok());
  EXPECT_EQ(unknown.error().message,
            "McapWriter::write(): unknown channel id 7 (add_channel() returned ids 1 to 2)");
  EXPECT_TRUE(writer->write(2, 0, 0, 0, mcap_bytes("x")));
  EXPECT_EQ(writer->statistics().message_count, 1u);  // the refused ones are not counted
}

TEST(McapWriter, CallsAfterCloseAreRefused) {
  test_files::TempDir dir("mcap_closed");
  auto writer = McapWriter::open(dir.file("x.mcap"));
  ASSERT_TRUE(writer.ok()) << writer.error().message;
  const std::uint16_t channel = writer->add_channel(0, "/a", "json");
  ASSERT_TRUE(writer->close());
  const std::uint64_t size = writer->bytes_written();

  Status write = writer->write(channel, 0, 0, 0, mcap_bytes("x"));
  ASSERT_FALSE(write.ok());
  EXPECT_EQ(write.error().message, "McapWriter::write(): the writer is closed");
  Status attach = writer->attach("a", "text/plain", 0, 0, mcap_bytes("x"));
  ASSERT_FALSE(attach.ok());
  EXPECT_EQ(attach.error().message, "McapWriter::attach(): the writer is closed");
  Status metadata = writer->metadata("m", {});
  ASSERT_FALSE(metadata.ok());
  EXPECT_EQ(metadata.error().message, "McapWriter::metadata(): the writer is closed");
  Status close = writer->close();
  ASSERT_FALSE(close.ok());
  EXPECT_EQ(close.error().message, "McapWriter::close(): the writer is closed");
  EXPECT_EQ(writer->add_schema("s", "", {}), 0);
  EXPECT_EQ(writer->add_channel(0, "/b", "json"), 0);
  EXPECT_EQ(std::filesystem::file_size(dir.file("x.mcap")), size);  // nothing appended
}

TEST(McapWriter, AFailedWriteIsReportedByEveryLaterCall) {
  if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full on this system";
  McapWriterOptions options;
  options.chunk_size = 64;  // the first message fills a chunk, whose flush fails
  auto writer = McapWriter::open("/dev/full", options);
  ASSERT_TRUE(writer.ok()) << writer.error().message;  // the header is still in stdio's buffer
  const std::uint16_t channel = writer->add_channel(0, "/a", "json");
  const std::string expected = "McapWriter: writing '/dev/full' failed: No space left on device";
  Status write = writer->write(channel, 0, 0, 0, mcap_bytes(std::string(100, 'x')));
  ASSERT_FALSE(write.ok());
  EXPECT_EQ(write.error().message, expected);
  Status again = writer->write(channel, 1, 0, 0, mcap_bytes("x"));
  ASSERT_FALSE(again.ok());
  EXPECT_EQ(again.error().message, expected);
  Status close = writer->close();
  ASSERT_FALSE(close.ok());
  EXPECT_EQ(close.error().message, expected);
}

}  // namespace
}  // namespace telear::record
