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
#include "telear/record/mcap_crc32.hpp"

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

std::string hex(std::uint32_t value) {
  char text[16];
  std::snprintf(text, sizeof(text), "0x%08x", value);
  return text;
}

std::string opcode_name(std::uint8_t opcode) {
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

bool parse_message(std::span<const std::uint8_t> content, MessageRecord& out) {
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
bool record_fits(std::span<const std::uint8_t> bytes, std::uint64_t at, std::uint64_t& length) {
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

// The Chunk record at `offset`, its records decompressed and checked against the chunk's CRC.
Result<std::vector<std::uint8_t>> ReaderFile::decompress_chunk(std::uint64_t offset,
                                                               ZSTD_DCtx* zstd) const {
  auto content = read_record(offset, kOpChunk, "Chunk");
  if (!content) return content.error();
  const std::string where = "chunk at offset " + std::to_string(offset);
  Fields f(*content);
  f.get<std::uint64_t>();  // message_start_time
  f.get<std::uint64_t>();  // message_end_time
  const auto uncompressed_size = f.get<std::uint64_t>();
  const auto uncompressed_crc = f.get<std::uint32_t>();
  const std::string compression = f.string();
  auto records = f.bytes(f.get<std::uint64_t>());
  if (f.failed()) return malformed("Chunk", offset);

  std::vector<std::uint8_t> out;
  if (compression.empty()) {
    if (records.size() != uncompressed_size) {
      return error(where + ": " + std::to_string(records.size()) +
                   " bytes of uncompressed records, but uncompressed_size says " +
                   std::to_string(uncompressed_size));
    }
    out.assign(records.begin(), records.end());
  } else if (compression == "zstd") {
    // The output grows as zstd produces it, up to one byte more than the chunk declares (which
    // reveals a chunk that inflates to more): a corrupt uncompressed_size cannot make the reader
    // allocate what the data does not hold. Where the frame's own content size agrees with the
    // chunk's, that size is allocated at once.
    const std::uint64_t cap = uncompressed_size == std::numeric_limits<std::uint64_t>::max()
                                  ? uncompressed_size
                                  : uncompressed_size + 1;
    const unsigned long long frame_size = ZSTD_getFrameContentSize(records.data(), records.size());
    std::uint64_t capacity =
        frame_size < ZSTD_CONTENTSIZE_ERROR && frame_size == uncompressed_size
            ? cap
            : std::min<std::uint64_t>(cap, std::max<std::uint64_t>(records.size() * 4, 1 << 16));
    out.resize(capacity);
    ZSTD_DCtx_reset(zstd, ZSTD_reset_session_only);
    ZSTD_inBuffer input{records.data(), records.size(), 0};
    std::size_t produced = 0;
    for (;;) {
      ZSTD_outBuffer output{out.data(), out.size(), produced};
      const std::size_t result = ZSTD_decompressStream(zstd, &output, &input);
      if (ZSTD_isError(result)) {
        return error(where + ": corrupt zstd data: " + ZSTD_getErrorName(result));
      }
      produced = output.pos;
      if (result == 0 && input.pos == input.size) break;  // every frame complete, input used up
      if (produced < out.size()) {
        // zstd stopped with room to spare: it wants input, and there is none left.
        if (input.pos == input.size) return error(where + ": zstd data ends inside a frame");
        continue;
      }
      if (out.size() >= cap) {
        return error(where + ": zstd data inflates to more than the chunk's uncompressed_size of " +
                     std::to_string(uncompressed_size) + " bytes");
      }
      out.resize(std::min<std::uint64_t>(cap, out.size() * 2));
    }
    if (produced != uncompressed_size) {
      return error(where + ": zstd data inflates to " + std::to_string(produced) +
                   " bytes, but uncompressed_size says " + std::to_string(uncompressed_size));
    }
    out.resize(produced);
  } else {
    return error(where + ": unsupported compression '" + compression +
                 "' (this reader reads zstd and uncompressed chunks)");
  }
  // A zero CRC means the writer did not compute one (spec).
  if (uncompressed_crc != 0) {
    const std::uint32_t crc = crc32(out.data(), out.size());
    if (crc != uncompressed_crc) {
      return error(where + ": CRC mismatch: the records' CRC-32 is " + hex(crc) +
                   ", the chunk says " + hex(uncompressed_crc));
    }
  }
  return out;
}

// Calls `visit(opcode, content, offset in records)` for each record of a chunk's records.
Status ReaderFile::for_each_record(
    std::span<const std::uint8_t> records, std::uint64_t chunk_offset,
    const std::function<Status(std::uint8_t, std::span<const std::uint8_t>, std::uint64_t)>& visit)
    const {
  for (std::uint64_t at = 0; at < records.size();) {
    std::uint64_t length = 0;
    if (!record_fits(records, at, length)) {
      return error("chunk at offset " + std::to_string(chunk_offset) + ": record at offset " +
                   std::to_string(at) + " of its " + std::to_string(records.size()) +
                   " uncompressed bytes runs past their end");
    }
    if (Status ok = visit(records[at], records.subspan(at + kPrefix, length), at); !ok) return ok;
    at += kPrefix + length;
  }
  return Status::Ok();
}

// Reads the footer and, where it points at one, the summary. `summarized` says whether the
// summary holds all the reader needs (statistics, and an index of every chunk, attachment and
// metadata record); if not, open() scans the data section.
Status ReaderFile::read_footer_and_summary(bool& summarized) {
  summarized = false;
  complete = false;
  if (size < 8 + kFooterRecord + 8) return Status::Ok();
  std::vector<std::uint8_t> footer;
  if (Status ok = read_at(size - 8 - kFooterRecord, kFooterRecord + 8, footer); !ok) return ok;
  std::uint64_t length = 0;
  std::memcpy(&length, footer.data() + 1, 8);
  if (footer[0] != kOpFooter || length != kFooterContent ||
      !std::equal(kMagic, kMagic + 8, footer.begin() + kFooterRecord)) {
    return Status::Ok();  // no footer: a file cut short
  }
  complete = true;
  const std::uint64_t footer_offset = size - 8 - kFooterRecord;
  Fields f(std::span<const std::uint8_t>(footer).subspan(kPrefix, kFooterContent));
  const auto summary_start = f.get<std::uint64_t>();
  const auto summary_offset_start = f.get<std::uint64_t>();
  const auto summary_crc = f.get<std::uint32_t>();
  if (summary_start == 0) return Status::Ok();  // a file written without a summary
  if (summary_start < 8 || summary_start > footer_offset ||
      (summary_offset_start != 0 &&
       (summary_offset_start < summary_start || summary_offset_start > footer_offset))) {
    return error("footer at offset " + std::to_string(footer_offset) +
                 " is corrupt: summary_start " + std::to_string(summary_start) +
                 " and summary_offset_start " + std::to_string(summary_offset_start) +
                 " are not offsets before the footer");
  }

  std::vector<std::uint8_t> summary;
  if (Status ok = read_at(summary_start, footer_offset - summary_start, summary); !ok) return ok;
  if (summary_crc != 0) {
    // The CRC covers the summary and summary offset sections and the footer up to its CRC.
    std::uint32_t crc = crc32_update(crc32_init(), summary.data(), summary.size());
    crc = crc32_final(crc32_update(crc, footer.data(), kPrefix + 16));
    if (crc != summary_crc) {
      return error("summary at offset " + std::to_string(summary_start) +
                   ": CRC mismatch: its CRC-32 is " + hex(crc) + ", the footer says " +
                   hex(summary_crc));
    }
  }

  bool have_statistics = false;
  std::uint64_t chunk_indexes = 0;
  std::uint64_t attachment_indexes = 0;
  std::uint64_t metadata_indexes = 0;
  std::span<const std::uint8_t> bytes(summary);
  for (std::uint64_t at = 0; at < bytes.size();) {
    const std::uint64_t offset = summary_start + at;
    std::uint64_t length = 0;
    if (!record_fits(bytes, at, length)) {
      return error("summary record at offset " + std::to_string(offset) +
                   " runs past the footer at offset " + std::to_string(footer_offset));
    }
    const std::uint8_t opcode = bytes[at];
    auto content = bytes.subspan(at + kPrefix, length);
    at += kPrefix + length;
    Fields r(content);
    switch (opcode) {
      case kOpSchema:
        if (Status ok = add_schema(content, offset); !ok) return ok;
        break;
      case kOpChannel:
        if (Status ok = add_channel(content, offset); !ok) return ok;
        break;
      case kOpStatistics: {
        McapStatistics& s = statistics;
        s.message_count = r.get<std::uint64_t>();
        s.schema_count = r.get<std::uint16_t>();
        s.channel_count = r.get<std::uint32_t>();
        s.attachment_count = r.get<std::uint32_t>();
        s.metadata_count = r.get<std::uint32_t>();
        s.chunk_count = r.get<std::uint32_t>();
        s.message_start_time = r.get<std::uint64_t>();
        s.message_end_time = r.get<std::uint64_t>();
        s.channel_message_counts = r.channel_map();
        if (r.failed()) return malformed("Statistics", offset);
        have_statistics = true;
        break;
      }
      case kOpChunkIndex: {
        McapSource source;
        source.start_time = r.get<std::uint64_t>();
        source.end_time = r.get<std::uint64_t>();
        source.offset = r.get<std::uint64_t>();
        r.get<std::uint64_t>();  // chunk_length: read_record() checks the record itself
        for (const auto& [channel, index_offset] : r.channel_map()) {
          source.channels.push_back(channel);
        }
        // Message indexes are optional: a chunk index without them says nothing of channels.
        source.channels_known = !source.channels.empty();
        r.get<std::uint64_t>();  // message_index_length
        r.string();              // compression, read from the chunk itself
        r.get<std::uint64_t>();  // compressed_size
        r.get<std::uint64_t>();  // uncompressed_size
        if (r.failed()) return malformed("Chunk Index", offset);
        sources.push_back(std::move(source));
        ++chunk_indexes;
        break;
      }
      case kOpAttachmentIndex:
        attachment_offsets.push_back(r.get<std::uint64_t>());
        if (r.failed()) return malformed("Attachment Index", offset);
        ++attachment_indexes;
        break;
      case kOpMetadataIndex:
        metadata_offsets.push_back(r.get<std::uint64_t>());
        if (r.failed()) return malformed("Metadata Index", offset);
        ++metadata_indexes;
        break;
      default:  // Summary Offset records (the groups are read in one pass), unknown opcodes
        break;
    }
  }
  // Indexes of messages outside chunks do not exist: a summary whose statistics count
  // messages but no chunks leaves them to a scan.
  summarized = have_statistics && chunk_indexes == statistics.chunk_count &&
               (statistics.message_count == 0 || chunk_indexes > 0) &&
               attachment_indexes == statistics.attachment_count &&
               metadata_indexes == statistics.metadata_count;
  return Status::Ok();
}

// Reads the records of [begin, limit): schemas and channels (also those inside chunks), every
// chunk (decompressed, to count its messages and check it), attachments' and metadata's
// offsets, until Data End or the footer. With `stop_at_cut`, a record that runs past `limit`
// ends the scan (the file was cut there) rather than failing it.
Status ReaderFile::scan(std::uint64_t begin, std::uint64_t limit, bool stop_at_cut) {
  sources.clear();
  attachment_offsets.clear();
  metadata_offsets.clear();
  McapStatistics s;
  ZstdDContext zstd(ZSTD_createDCtx());
  if (!zstd) return error("zstd could not allocate its context");
  auto count = [&](const MessageRecord& message, McapSource& source, bool first) {
    if (s.message_count == 0) {
      s.message_start_time = s.message_end_time = message.log_time;
    } else {
      s.message_start_time = std::min(s.message_start_time, message.log_time);
      s.message_end_time = std::max(s.message_end_time, message.log_time);
    }
    if (first) {
      source.start_time = source.end_time = message.log_time;
    } else {
      source.start_time = std::min(source.start_time, message.log_time);
      source.end_time = std::max(source.end_time, message.log_time);
    }
    if (std::find(source.channels.begin(), source.channels.end(), message.channel_id) ==
        source.channels.end()) {
      source.channels.push_back(message.channel_id);
    }
    ++s.message_count;
    ++s.channel_message_counts[message.channel_id];
  };

  std::vector<std::uint8_t> content;
  std::uint64_t at = begin;
  tail = 0;
  while (at < limit) {
    if (stop_at_cut && limit - at < kPrefix) break;
    auto prefix = read_prefix(at, limit);
    if (!prefix) {
      if (stop_at_cut) break;
      return prefix.error();
    }
    const std::uint64_t offset = at;
    const std::uint8_t opcode = prefix->opcode;
    if (opcode == kOpDataEnd || opcode == kOpFooter) {
      at = limit;
      break;
    }
    at = prefix->end;
    switch (opcode) {
      case kOpSchema:
      case kOpChannel: {
        if (Status ok = read_at(offset + kPrefix, prefix->length, content); !ok) return ok;
        Status added =
            opcode == kOpSchema ? add_schema(content, offset) : add_channel(content, offset);
        if (!added) return added;
        break;
      }
      case kOpMessage: {
        if (Status ok = read_at(offset + kPrefix, prefix->length, content); !ok) return ok;
        MessageRecord message;
        if (!parse_message(content, message)) return malformed("Message", offset);
        McapSource source;
        source.offset = offset;
        source.loose_message = true;
        source.channels_known = true;
        count(message, source, true);
        sources.push_back(std::move(source));
        break;
      }
      case kOpChunk: {
        auto records = decompress_chunk(offset, zstd.get());
        if (!records) return records.error();
        McapSource source;
        source.offset = offset;
        source.channels_known = true;
        bool first = true;
        Status read = for_each_record(
            *records, offset,
            [&](std::uint8_t op, std::span<const std::uint8_t> record,
                std::uint64_t in_chunk) -> Status {
              const std::uint64_t where = offset;  // records inside a chunk: name the chunk
              if (op == kOpSchema) return add_schema(record, where);
              if (op == kOpChannel) return add_channel(record, where);
              if (op != kOpMessage) return Status::Ok();
              MessageRecord message;
              if (!parse_message(record, message)) {
                return error("chunk at offset " + std::to_string(offset) +
                             ": Message record at offset " + std::to_string(in_chunk) +
                             " of its records is shorter than a message's fields");
              }
              count(message, source, first);
              first = false;
              return Status::Ok();
            });
        if (!read) return read;
        ++s.chunk_count;
        if (!first) sources.push_back(std::move(source));
        break;
      }
      case kOpAttachment:
        attachment_offsets.push_back(offset);
        break;
      case kOpMetadata:
        metadata_offsets.push_back(offset);
        break;
      default:  // Header (read by open()), message indexes, unknown opcodes: skipped
        break;
    }
  }
  if (at < limit) tail = limit - at;
  s.schema_count = static_cast<std::uint16_t>(schemas.size());
  s.channel_count = static_cast<std::uint32_t>(channels.size());
  s.attachment_count = static_cast<std::uint32_t>(attachment_offsets.size());
  s.metadata_count = static_cast<std::uint32_t>(metadata_offsets.size());
  for (const auto& [id, channel] : channels) s.channel_message_counts.try_emplace(id, 0);
  statistics = std::move(s);
  return Status::Ok();
}

Status ReaderFile::open(const std::string& file_path) {
  path = file_path;
  fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return error(std::string("cannot open: ") + std::strerror(errno));
  struct stat info {};
  if (::fstat(fd, &info) != 0) return error(std::string("cannot stat: ") + std::strerror(errno));
  if (!S_ISREG(info.st_mode)) return error("not a regular file");
  size = static_cast<std::uint64_t>(info.st_size);

  std::vector<std::uint8_t> magic;
  if (size < 8) {
    return Error{"not an MCAP file: '" + path + "' is " + std::to_string(size) +
                 " bytes long, shorter than the 8-byte MCAP magic"};
  }
  if (Status ok = read_at(0, 8, magic); !ok) return ok;
  if (!std::equal(kMagic, kMagic + 8, magic.begin())) {
    return Error{"not an MCAP file: '" + path + "' does not start with the MCAP magic"};
  }
  auto header = read_prefix(8, size);
  if (!header) {
    return error("the file ends inside its Header record at offset 8 (" + std::to_string(size) +
                 " bytes in all)");
  }
  if (header->opcode != kOpHeader) {
    return error("expected the Header record (opcode 0x01) at offset 8, found opcode " +
                 opcode_name(header->opcode));
  }
  auto header_content = read_record(8, kOpHeader, "Header");
  if (!header_content) return header_content.error();
  Fields f(*header_content);
  profile = f.string();
  library = f.string();
  if (f.failed()) return malformed("Header", 8);

  bool summarized = false;
  if (Status ok = read_footer_and_summary(summarized); !ok) return ok;
  if (!summarized) {
    // A closed file is scanned up to its footer, and must be whole up to there; a cut one up to
    // its last complete record.
    const std::uint64_t limit = complete ? size - 8 - kFooterRecord : size;
    if (Status ok = scan(header->end, limit, /*stop_at_cut=*/!complete); !ok) {
      return ok;
    }
  }
  return Status::Ok();
}

}  // namespace mcap_reader_detail

struct McapReader::State : mcap_reader_detail::ReaderFile {};

Result<McapReader> McapReader::open(const std::string& path) {
  auto state = std::make_unique<State>();
  if (Status ok = state->open(path); !ok) return ok.error();
  return McapReader(std::move(state));
}

McapReader::McapReader(std::unique_ptr<State> state) : state_(std::move(state)) {}
McapReader::McapReader(McapReader&&) noexcept = default;
McapReader& McapReader::operator=(McapReader&&) noexcept = default;
McapReader::~McapReader() = default;

bool McapReader::complete() const {
  return state_->complete;
}
std::uint64_t McapReader::unread_tail_bytes() const {
  return state_->tail;
}
std::uint64_t McapReader::file_size() const {
  return state_->size;
}
const std::string& McapReader::profile() const {
  return state_->profile;
}
const std::string& McapReader::library() const {
  return state_->library;
}
const std::map<std::uint16_t, McapSchema>& McapReader::schemas() const {
  return state_->schemas;
}
const std::map<std::uint16_t, McapChannel>& McapReader::channels() const {
  return state_->channels;
}
const McapStatistics& McapReader::statistics() const {
  return state_->statistics;
}

Status McapReader::read_messages(const std::function<bool(const McapMessageView&)>& visit,
                                 const McapReadOptions& options) const {
  return state_->read_messages(visit, options);
}
Result<std::vector<McapAttachment>> McapReader::attachments() const {
  return state_->attachments();
}
Result<std::vector<McapMetadata>> McapReader::metadata() const {
  return state_->metadata();
}

namespace mcap_reader_detail {

Status ReaderFile::read_messages(const std::function<bool(const McapMessageView&)>& visit,
                                 const McapReadOptions& options) const {
  if (options.start_ns > options.end_ns) return Status::Ok();
  std::set<std::uint16_t> wanted;  // empty: every channel
  if (!options.topics.empty()) {
    for (const auto& [id, channel] : channels) {
      if (std::find(options.topics.begin(), options.topics.end(), channel.topic) !=
          options.topics.end()) {
        wanted.insert(id);
      }
    }
    if (wanted.empty()) return Status::Ok();
  }
  auto channel_wanted = [&](std::uint16_t id) { return wanted.empty() || wanted.count(id) > 0; };

  // The sources that may hold a wanted message, by start time: the merge below loads them in
  // that order.
  std::vector<const McapSource*> selected;
  for (const McapSource& source : sources) {
    if (source.end_time < options.start_ns || source.start_time > options.end_ns) continue;
    if (source.channels_known && !wanted.empty() &&
        std::none_of(source.channels.begin(), source.channels.end(), channel_wanted)) {
      continue;
    }
    selected.push_back(&source);
  }
  std::stable_sort(selected.begin(), selected.end(), [](const McapSource* a, const McapSource* b) {
    return a->start_time < b->start_time;
  });

  // Messages of the loaded sources, smallest (log time, source offset, offset in source) first:
  // log-time order, ties in file order.
  struct Pending {
    std::uint64_t log_time;
    std::uint64_t source_offset;
    std::uint64_t record_offset;
    std::size_t source;  // index into `buffers`
    MessageRecord message;
  };
  auto later = [](const Pending& a, const Pending& b) {
    return std::tie(a.log_time, a.source_offset, a.record_offset) >
           std::tie(b.log_time, b.source_offset, b.record_offset);
  };
  std::priority_queue<Pending, std::vector<Pending>, decltype(later)> pending(later);
  std::vector<std::vector<std::uint8_t>> buffers(selected.size());
  std::vector<std::size_t> unvisited(selected.size(), 0);

  ZstdDContext zstd(ZSTD_createDCtx());
  if (!zstd) return error("zstd could not allocate its context");
  auto load = [&](std::size_t index) -> Status {
    const McapSource& source = *selected[index];
    std::vector<std::uint8_t>& buffer = buffers[index];
    if (source.loose_message) {
      auto prefix = read_prefix(source.offset, size);
      if (!prefix) return prefix.error();
      if (Status ok = read_at(source.offset, prefix->end - source.offset, buffer); !ok) return ok;
    } else {
      auto records = decompress_chunk(source.offset, zstd.get());
      if (!records) return records.error();
      buffer = std::move(*records);
    }
    return for_each_record(
        buffer, source.offset,
        [&](std::uint8_t opcode, std::span<const std::uint8_t> record, std::uint64_t at) -> Status {
          if (opcode != kOpMessage) return Status::Ok();
          MessageRecord message;
          if (!parse_message(record, message)) {
            return error("Message record at offset " + std::to_string(at) +
                         (source.loose_message
                              ? std::string()
                              : " of the chunk at offset " + std::to_string(source.offset)) +
                         " is shorter than a message's fields");
          }
          if (message.log_time < options.start_ns || message.log_time > options.end_ns ||
              !channel_wanted(message.channel_id)) {
            return Status::Ok();
          }
          if (channels.count(message.channel_id) == 0) {
            return error("a message in the " +
                         std::string(source.loose_message ? "record" : "chunk") + " at offset " +
                         std::to_string(source.offset) + " is on channel " +
                         std::to_string(message.channel_id) + ", which the file never defines");
          }
          pending.push(Pending{message.log_time, source.offset, at, index, message});
          ++unvisited[index];
          return Status::Ok();
        });
  };

  std::size_t next = 0;
  for (;;) {
    // A source not loaded yet starts no earlier than selected[next]; while that is at or before
    // the earliest pending message, it may hold an earlier one, so it is loaded first.
    while (next < selected.size() &&
           (pending.empty() || selected[next]->start_time <= pending.top().log_time)) {
      if (Status ok = load(next); !ok) return ok;
      if (unvisited[next] == 0) buffers[next] = {};
      ++next;
    }
    if (pending.empty()) break;
    const Pending top = pending.top();
    pending.pop();
    McapMessageView view;
    view.channel_id = top.message.channel_id;
    view.topic = channels.at(top.message.channel_id).topic;
    view.sequence = top.message.sequence;
    view.log_time = top.message.log_time;
    view.publish_time = top.message.publish_time;
    view.data = top.message.data;
    if (!visit(view)) return Status::Ok();
    if (--unvisited[top.source] == 0) buffers[top.source] = {};  // the chunk is done
  }
  return Status::Ok();
}

Result<std::vector<McapAttachment>> ReaderFile::attachments() const {
  std::vector<McapAttachment> out;
  for (std::uint64_t offset : attachment_offsets) {
    auto content = read_record(offset, kOpAttachment, "Attachment");
    if (!content) return content.error();
    Fields f(*content);
    McapAttachment attachment;
    attachment.log_time = f.get<std::uint64_t>();
    attachment.create_time = f.get<std::uint64_t>();
    attachment.name = f.string();
    attachment.media_type = f.string();
    auto data = f.bytes(f.get<std::uint64_t>());
    const std::uint64_t crc_at = f.at();
    const auto stored_crc = f.get<std::uint32_t>();
    if (f.failed()) return malformed("Attachment", offset);
    // The CRC covers every field before it; zero means none was computed.
    if (stored_crc != 0) {
      const std::uint32_t crc = crc32(content->data(), crc_at);
      if (crc != stored_crc) {
        return error("attachment '" + attachment.name + "' at offset " + std::to_string(offset) +
                     ": CRC mismatch: its CRC-32 is " + hex(crc) + ", the record says " +
                     hex(stored_crc));
      }
    }
    attachment.data.assign(data.begin(), data.end());
    out.push_back(std::move(attachment));
  }
  return out;
}

Result<std::vector<McapMetadata>> ReaderFile::metadata() const {
  std::vector<McapMetadata> out;
  for (std::uint64_t offset : metadata_offsets) {
    auto content = read_record(offset, kOpMetadata, "Metadata");
    if (!content) return content.error();
    Fields f(*content);
    McapMetadata metadata;
    metadata.name = f.string();
    metadata.entries = f.string_map();
    if (f.failed()) return malformed("Metadata", offset);
    out.push_back(std::move(metadata));
  }
  return out;
}

}  // namespace mcap_reader_detail
}  // namespace telear::record
