#pragma once
// An MCAP file reader (https://mcap.dev/spec, major version 0), over libzstd, for the files
// McapWriter writes and any other writer's that follow the specification; `telear replay` and
// `telear report` read recordings through it.
//
// A closed file is read through its summary: open() reads the footer, then the summary's
// schemas, channels, statistics and chunk, attachment and metadata indexes; read_messages()
// reads only the chunks whose time range (and channels) the read asks for. A file without a
// valid footer (a recorder killed mid-recording: McapWriter flushes each chunk whole, the summary
// only at close) is read as @mcap/core's stream reader reads it: open() scans its records from
// the start up to the last complete one, decompressing every chunk to count its messages, and
// complete() is false. A closed file whose summary lacks statistics or indexes is scanned too.
//
// The reader holds the file open and reads it piece by piece (a chunk, an attachment) as it is
// asked: recordings with camera streams run to gigabytes, more than it should hold in memory.
//
// Bad input is an Error, never a crash: every length is checked against its record and the file
// before it is used, and the messages say what is wrong and at which byte offset. Records with
// opcodes the reader does not know are skipped, as the specification asks. Messages written
// outside chunks are read when the file is scanned; a summary's chunk indexes cannot point at
// them, so a summarized file's loose messages are not (McapWriter writes none).

#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/record/mcap_writer.hpp"  // McapBytes, McapStatistics

namespace telear::record {

struct McapSchema {
  std::uint16_t id = 0;
  std::string name;
  std::string encoding;  // "protobuf", "jsonschema", ...
  std::vector<std::uint8_t> data;
};

struct McapChannel {
  std::uint16_t id = 0;
  std::uint16_t schema_id = 0;  // 0: no schema
  std::string topic;
  std::string message_encoding;
  std::map<std::string, std::string> metadata;
};

// One message as read_messages() hands it to its visitor: `topic` and `data` point into the
// reader's buffers and are valid only during the visit (copy what is kept).
struct McapMessageView {
  std::uint16_t channel_id = 0;
  std::string_view topic;
  std::uint32_t sequence = 0;
  std::uint64_t log_time = 0;      // ns, the recorder's clock
  std::uint64_t publish_time = 0;  // ns, the sender's clock
  McapBytes data;
};

struct McapAttachment {
  std::string name;
  std::string media_type;
  std::uint64_t log_time = 0;
  std::uint64_t create_time = 0;
  std::vector<std::uint8_t> data;
};

// A Metadata record. A file may hold several records of one name, so they are listed in file
// order rather than keyed by name.
struct McapMetadata {
  std::string name;
  std::map<std::string, std::string> entries;
};

struct McapReadOptions {
  // Log times to read, both ends included (ns).
  std::uint64_t start_ns = 0;
  std::uint64_t end_ns = std::numeric_limits<std::uint64_t>::max();
  // Topics to read; empty reads every topic. A topic no channel has matches nothing.
  std::vector<std::string> topics;
};

class McapReader {
 public:
  // Opens the file at `path` and reads its summary, or scans it where it has none (see above).
  static Result<McapReader> open(const std::string& path);

  McapReader(McapReader&&) noexcept;
  McapReader& operator=(McapReader&&) noexcept;
  McapReader(const McapReader&) = delete;
  McapReader& operator=(const McapReader&) = delete;
  ~McapReader();

  // Whether the file ends with its footer and closing magic (the writer closed it). When false
  // the file was read up to its last complete record and unread_tail_bytes() follow it.
  bool complete() const;
  std::uint64_t unread_tail_bytes() const;
  std::uint64_t file_size() const;

  // The Header record's fields.
  const std::string& profile() const;
  const std::string& library() const;

  const std::map<std::uint16_t, McapSchema>& schemas() const;
  const std::map<std::uint16_t, McapChannel>& channels() const;
  // The summary's Statistics record, or the same counts from a scan of the file.
  const McapStatistics& statistics() const;

  // Calls `visit` with each message in `options`' time range and topics, in log-time order
  // (messages of equal log time in file order), until it returns false. Chunks may overlap in
  // time; each is decompressed when the merge reaches its start time, and released once its
  // messages are visited. A chunk that cannot be read (corrupt zstd data, a CRC mismatch, a
  // record past its end) ends the read with an Error naming its offset; messages before it in
  // log-time order have been visited by then.
  Status read_messages(const std::function<bool(const McapMessageView&)>& visit,
                       const McapReadOptions& options = {}) const;

  // Every attachment (data included) and Metadata record, in file order, read from the file
  // now; an attachment whose CRC does not match its bytes is an Error.
  Result<std::vector<McapAttachment>> attachments() const;
  Result<std::vector<McapMetadata>> metadata() const;

 private:
  struct State;
  explicit McapReader(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

}  // namespace telear::record
