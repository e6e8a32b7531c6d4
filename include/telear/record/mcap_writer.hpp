#pragma once
// An MCAP file writer (https://mcap.dev/spec, major version 0), over libzstd; no other
// dependency, so any layer may record.
//
// The file it writes:
//
//   <magic> Header
//   Schema* Channel*          each written once, outside chunks, when it is added
//   ( Chunk MessageIndex*     a chunk of Message records, then one index per channel in it
//   | Attachment | Metadata )*
//   DataEnd                   the CRC32 of every byte before it
//   Schema* Channel* Statistics ChunkIndex* AttachmentIndex* MetadataIndex*   (summary)
//   SummaryOffset*            one per group of the summary
//   Footer <magic>
//
// Messages are buffered into a chunk of about `chunk_size` uncompressed bytes; a full chunk is
// compressed and written, with its message indexes, at once, and the stream is flushed to the
// operating system. Schemas and channels are written before the first chunk that uses them,
// attachments and metadata when they are given. So a recorder that crashes or is killed
// leaves a file that a streaming reader reads up to its last complete chunk: only the messages
// of the chunk being filled, and the summary, are lost (docs/recording.md). close() writes the
// last chunk and the summary; the destructor closes an open writer.
//
// Errors of the file system (cannot create, a failed write) are returned as Results; once a
// write has failed, every later call returns that error. A message on a channel this writer
// never added, or any call after close(), is refused with a Status saying so.

#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "telear/core/result.hpp"

namespace telear::record {

// Bytes to record (a message, a schema's data, an attachment); see mcap_bytes() for strings
// such as protobuf's SerializeToString output.
using McapBytes = std::span<const std::uint8_t>;

inline McapBytes mcap_bytes(std::string_view text) {
  return {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()};
}

enum class McapCompression { kNone, kZstd };

struct McapWriterOptions {
  // The Header record's fields: the profile names the conventions of the file's encodings
  // ("" for none; Foxglove's protobuf schemas need none), library the program that wrote it.
  std::string profile;
  std::string library = "telear";
  // Uncompressed bytes of Message records after which a chunk is written. Larger chunks
  // compress better; smaller ones lose less to a crash and cost readers less to seek into.
  std::uint64_t chunk_size = 1024 * 1024;
  McapCompression compression = McapCompression::kZstd;
  // zstd's level (ZSTD_minCLevel() .. ZSTD_maxCLevel(), 0 meaning zstd's default of 3). Level 1
  // keeps up with live streams on one core (bench/mcap_writer_bench.cpp); camera frames are
  // JPEG already, which no level shrinks.
  int zstd_level = 1;

  // Whether the options can be used; if not, *error (when given) says which field and why.
  bool is_valid(std::string* error = nullptr) const;
};

// What close() counts into the Statistics record; also readable while writing.
struct McapStatistics {
  std::uint64_t message_count = 0;
  std::uint16_t schema_count = 0;
  std::uint32_t channel_count = 0;
  std::uint32_t attachment_count = 0;
  std::uint32_t metadata_count = 0;
  std::uint32_t chunk_count = 0;         // chunks written so far (the one being filled not counted)
  std::uint64_t message_start_time = 0;  // earliest log time, ns; 0 while there is no message
  std::uint64_t message_end_time = 0;    // latest log time, ns
  std::map<std::uint16_t, std::uint64_t> channel_message_counts;  // every channel, 0 included
};

class McapWriter {
 public:
  // Creates (truncates) the file at `path` and writes the magic and the Header record.
  static Result<McapWriter> open(const std::string& path, const McapWriterOptions& options = {});

  McapWriter(McapWriter&&) noexcept;
  McapWriter& operator=(McapWriter&&) noexcept;
  McapWriter(const McapWriter&) = delete;
  McapWriter& operator=(const McapWriter&) = delete;
  ~McapWriter();  // close()s an open writer, its error unreported

  // A schema, written to the file at once; returns its id (1, 2, ...; 0 means "no schema" in
  // MCAP). `encoding` is e.g. "protobuf" (data: a serialized FileDescriptorSet) or "jsonschema".
  // After close() or a failed write nothing is written and 0 is returned; the next write() or
  // close() reports why.
  std::uint16_t add_schema(std::string_view name, std::string_view encoding, McapBytes data);

  // A channel on `topic` whose messages are `message_encoding` ("protobuf", "json", ...) under
  // schema `schema_id` (a value add_schema returned, or 0 for none), written to the file at
  // once; returns its id (1, 2, ...). An unknown schema id is a programmer error (asserted).
  // After close() or a failed write, returns 0 as add_schema does.
  std::uint16_t add_channel(std::uint16_t schema_id, std::string_view topic,
                            std::string_view message_encoding,
                            const std::map<std::string, std::string>& metadata = {});

  // One message on `channel_id`, logged at `log_time_ns` (the recorder's clock) and published
  // at `publish_time_ns` (the sender's; pass the log time where there is none). Buffered into
  // the current chunk, which is written when it reaches chunk_size.
  Status write(std::uint16_t channel_id, std::uint32_t sequence, std::uint64_t log_time_ns,
               std::uint64_t publish_time_ns, McapBytes data);

  // A file embedded in the recording (e.g. the robot's URDF), written at once, outside chunks.
  Status attach(std::string_view name, std::string_view media_type, std::uint64_t log_time_ns,
                std::uint64_t create_time_ns, McapBytes data);

  // A named set of key-value pairs (e.g. "session": {"robot": "puma560", ...}), written at once.
  Status metadata(std::string_view name, const std::map<std::string, std::string>& entries);

  // Writes the last chunk, the data end, the summary, the footer and the closing magic, and
  // closes the file. A second close() is refused like any other call after close.
  Status close();

  const McapStatistics& statistics() const;
  // Bytes written to the file so far (the chunk being filled not included).
  std::uint64_t bytes_written() const;

 private:
  struct State;
  explicit McapWriter(std::unique_ptr<State> state);
  void finish() noexcept;  // close() if open, error unreported; release the file
  std::unique_ptr<State> state_;
};

}  // namespace telear::record
