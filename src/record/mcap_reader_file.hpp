#pragma once
// Internal to record: the MCAP reader's open file (ReaderFile, McapReader's State) and the
// record-level helpers its two sources share -- mcap_reader.cpp (opening: the footer and summary,
// or a scan) and mcap_reader_messages.cpp (messages in log-time order, attachments, metadata).

#include "telear/record/mcap_reader.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zstd.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <queue>
#include <set>
#include <span>
#include <tuple>
#include <utility>

#include "mcap_format.hpp"
#include "telear/core/crc32.hpp"

namespace telear::record {
// Named rather than anonymous: McapReader::State derives from ReaderFile, and the library is
// built as one unity source in which an anonymous namespace would merge with the writer's.
namespace mcap_reader_detail {

using namespace mcap_format;  // NOLINT(google-build-using-namespace): the format's names
constexpr std::uint64_t kPrefix = kRecordPrefix;
constexpr std::uint64_t kFooterContent = 8 + 8 + 4;
constexpr std::uint64_t kFooterRecord = kPrefix + kFooterContent;

// Fields are read by copying little-endian bytes into native integers.
static_assert(std::endian::native == std::endian::little);

inline std::string hex(std::uint32_t value) {
  char text[16];
  std::snprintf(text, sizeof(text), "0x%08x", value);
  return text;
}

inline std::string opcode_name(std::uint8_t opcode) {
  char text[8];
  std::snprintf(text, sizeof(text), "0x%02x", opcode);
  return text;
}

// Reads a record's fields in order; a read past the end of the content marks the reader failed
// and returns empty values, so a parser reads all its fields and checks failed() once.
class Fields {
 public:
  explicit Fields(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}

  template <typename T>
  T get() {
    T value{};
    if (take(sizeof(T))) std::memcpy(&value, bytes_.data() + at_ - sizeof(T), sizeof(T));
    return value;
  }
  std::span<const std::uint8_t> bytes(std::uint64_t n) {
    if (!take(n)) return {};
    return bytes_.subspan(at_ - n, n);
  }
  std::string string() {
    auto text = bytes(get<std::uint32_t>());
    return {reinterpret_cast<const char*>(text.data()), text.size()};
  }
  std::map<std::string, std::string> string_map() {
    std::map<std::string, std::string> map;
    Fields entries(bytes(get<std::uint32_t>()));
    while (!entries.failed_ && entries.left() > 0) {
      std::string key = entries.string();
      map[std::move(key)] = entries.string();
    }
    failed_ = failed_ || entries.failed_;
    return map;
  }
  // Map<uint16, uint64>, the shape of the statistics' and chunk indexes' per-channel maps.
  std::map<std::uint16_t, std::uint64_t> channel_map() {
    std::map<std::uint16_t, std::uint64_t> map;
    Fields entries(bytes(get<std::uint32_t>()));
    while (!entries.failed_ && entries.left() > 0) {
      const auto channel = entries.get<std::uint16_t>();
      map[channel] = entries.get<std::uint64_t>();
    }
    failed_ = failed_ || entries.failed_;
    return map;
  }

  bool failed() const { return failed_; }
  std::uint64_t at() const { return at_; }
  std::uint64_t left() const { return bytes_.size() - at_; }

 private:
  bool take(std::uint64_t n) {
    if (failed_ || n > bytes_.size() - at_) {
      failed_ = true;
      return false;
    }
    at_ += n;
    return true;
  }

  std::span<const std::uint8_t> bytes_;
  std::uint64_t at_ = 0;
  bool failed_ = false;
};

struct ZstdDContextDeleter {
  void operator()(ZSTD_DCtx* context) const { ZSTD_freeDCtx(context); }
};
using ZstdDContext = std::unique_ptr<ZSTD_DCtx, ZstdDContextDeleter>;

// One parsed Message record, its data pointing into a buffer of records.
struct MessageRecord {
  std::uint16_t channel_id = 0;
  std::uint32_t sequence = 0;
  std::uint64_t log_time = 0;
  std::uint64_t publish_time = 0;
  McapBytes data;
};

inline bool parse_message(std::span<const std::uint8_t> content, MessageRecord& out) {
  if (content.size() < kMessageFields) return false;
  Fields f(content);
  out.channel_id = f.get<std::uint16_t>();
  out.sequence = f.get<std::uint32_t>();
  out.log_time = f.get<std::uint64_t>();
  out.publish_time = f.get<std::uint64_t>();
  out.data = content.subspan(kMessageFields);
  return true;
}

// Whether a record (9-byte prefix and content) starts at `at` in `bytes` and ends within them;
// if so, `length` is its content's length.
inline bool record_fits(std::span<const std::uint8_t> bytes, std::uint64_t at,
                        std::uint64_t& length) {
  if (at > bytes.size() || bytes.size() - at < kPrefix) return false;
  std::memcpy(&length, bytes.data() + at + 1, 8);
  return length <= bytes.size() - at - kPrefix;
}

// Where messages come from: a Chunk record or, in a scanned file, a Message record outside any
// chunk (read as a one-message "chunk" so that the merge treats both alike).
struct McapSource {
  std::uint64_t offset = 0;  // of the record's opcode
  std::uint64_t start_time = 0;
  std::uint64_t end_time = 0;
  bool loose_message = false;
  // The channels with messages in it, when known (a chunk index's message index offsets, or a
  // scan): lets a topic filter skip a chunk without decompressing it.
  bool channels_known = false;
  std::vector<std::uint16_t> channels;
};

// The open file and what open() found in it; McapReader's State.
struct ReaderFile {
  std::string path;
  int fd = -1;
  std::uint64_t size = 0;
  bool complete = false;
  std::uint64_t tail = 0;
  std::string profile;
  std::string library;
  std::map<std::uint16_t, McapSchema> schemas;
  std::map<std::uint16_t, McapChannel> channels;
  McapStatistics statistics;
  std::vector<McapSource> sources;
  std::vector<std::uint64_t> attachment_offsets;
  std::vector<std::uint64_t> metadata_offsets;

  ReaderFile() = default;
  ReaderFile(const ReaderFile&) = delete;  // owns `fd`
  ReaderFile& operator=(const ReaderFile&) = delete;
  ~ReaderFile() {
    if (fd >= 0) ::close(fd);
  }

  Error error(const std::string& what) const {
    return Error{"McapReader: '" + path + "': " + what};
  }

  // Reads [offset, offset + n) of the file into `out`; a range past the end is an error.
  Status read_at(std::uint64_t offset, std::uint64_t n, std::vector<std::uint8_t>& out) const {
    if (offset > size || n > size - offset) {
      return error("reading " + std::to_string(n) + " bytes at offset " + std::to_string(offset) +
                   " runs past the end of the file (" + std::to_string(size) + " bytes)");
    }
    out.resize(n);
    std::uint64_t done = 0;
    while (done < n) {
      const ssize_t got =
          ::pread(fd, out.data() + done, n - done, static_cast<off_t>(offset + done));
      if (got < 0 && errno == EINTR) continue;
      if (got <= 0) {
        return error("reading at offset " + std::to_string(offset + done) + " failed: " +
                     (got < 0 ? std::strerror(errno) : "the file shrank while being read"));
      }
      done += static_cast<std::uint64_t>(got);
    }
    return Status::Ok();
  }

  // A record's opcode and content length at `offset`, checked to end within [offset, limit).
  struct Prefix {
    std::uint8_t opcode = 0;
    std::uint64_t length = 0;
    std::uint64_t end = 0;  // offset past the record
  };
  Result<Prefix> read_prefix(std::uint64_t offset, std::uint64_t limit) const {
    std::vector<std::uint8_t> bytes;
    if (offset > limit || limit - offset < kPrefix) {
      return error("record at offset " + std::to_string(offset) +
                   " is cut off: " + std::to_string(limit - std::min(limit, offset)) +
                   " bytes left for its 9-byte opcode and length");
    }
    if (Status ok = read_at(offset, kPrefix, bytes); !ok) return ok.error();
    Prefix prefix;
    prefix.opcode = bytes[0];
    std::memcpy(&prefix.length, bytes.data() + 1, 8);
    if (prefix.length > limit - offset - kPrefix) {
      return error("record at offset " + std::to_string(offset) + " (opcode " +
                   opcode_name(prefix.opcode) + ") has length " + std::to_string(prefix.length) +
                   ", beyond the " + std::to_string(limit - offset - kPrefix) +
                   " bytes left before offset " + std::to_string(limit));
    }
    prefix.end = offset + kPrefix + prefix.length;
    return prefix;
  }

  // The content of the record at `offset`, which must have opcode `expected` (named `what`).
  Result<std::vector<std::uint8_t>> read_record(std::uint64_t offset, std::uint8_t expected,
                                                const char* what) const {
    auto prefix = read_prefix(offset, size);
    if (!prefix) return prefix.error();
    if (prefix->opcode != expected) {
      return error("expected a " + std::string(what) + " record (opcode " + opcode_name(expected) +
                   ") at offset " + std::to_string(offset) + ", found opcode " +
                   opcode_name(prefix->opcode));
    }
    std::vector<std::uint8_t> content;
    if (Status ok = read_at(offset + kPrefix, prefix->length, content); !ok) return ok.error();
    return content;
  }

  Error malformed(const char* what, std::uint64_t offset) const {
    return error(std::string(what) + " record at offset " + std::to_string(offset) +
                 " is malformed: its fields run past its length");
  }

  Status add_schema(std::span<const std::uint8_t> content, std::uint64_t offset) {
    Fields f(content);
    McapSchema schema;
    schema.id = f.get<std::uint16_t>();
    schema.name = f.string();
    schema.encoding = f.string();
    auto data = f.bytes(f.get<std::uint32_t>());
    if (f.failed()) return malformed("Schema", offset);
    schema.data.assign(data.begin(), data.end());
    schemas[schema.id] = std::move(schema);
    return Status::Ok();
  }
  Status add_channel(std::span<const std::uint8_t> content, std::uint64_t offset) {
    Fields f(content);
    McapChannel channel;
    channel.id = f.get<std::uint16_t>();
    channel.schema_id = f.get<std::uint16_t>();
    channel.topic = f.string();
    channel.message_encoding = f.string();
    channel.metadata = f.string_map();
    if (f.failed()) return malformed("Channel", offset);
    channels[channel.id] = std::move(channel);
    return Status::Ok();
  }

  Result<std::vector<std::uint8_t>> decompress_chunk(std::uint64_t offset, ZSTD_DCtx* zstd) const;
  Status for_each_record(std::span<const std::uint8_t> records, std::uint64_t chunk_offset,
                         const std::function<Status(std::uint8_t, std::span<const std::uint8_t>,
                                                    std::uint64_t)>& visit) const;
  Status read_footer_and_summary(bool& summarized);
  Status scan(std::uint64_t begin, std::uint64_t limit, bool stop_at_cut);
  Status open(const std::string& file_path);
  Status read_messages(const std::function<bool(const McapMessageView&)>& visit,
                       const McapReadOptions& options) const;
  Result<std::vector<McapAttachment>> attachments() const;
  Result<std::vector<McapMetadata>> metadata() const;
};

}  // namespace mcap_reader_detail
}  // namespace telear::record
