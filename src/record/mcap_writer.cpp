#include "telear/record/mcap_writer.hpp"

#include <zstd.h>

#include <algorithm>
#include <bit>
#include <cassert>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "mcap_format.hpp"
#include "telear/core/crc32.hpp"

namespace telear::record {
// Named rather than anonymous: McapWriter::State, which has external linkage, holds these.
namespace mcap_detail {

using namespace mcap_format;  // NOLINT(google-build-using-namespace): the format's names

// Fields are stored little-endian (the spec's byte order) by copying the native
// representation, so the writer builds only for little-endian machines.
static_assert(std::endian::native == std::endian::little);

// A growable byte buffer whose growth leaves new bytes uninitialised (std::vector zeroes
// them, a second pass over every recorded byte), with MCAP's field encodings.
class McapBuffer {
 public:
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  const std::uint8_t* data() const { return data_.get(); }
  std::uint8_t* data() { return data_.get(); }
  void clear() { size_ = 0; }

  // Room for n more bytes at the end; returns where they start.
  std::uint8_t* grow(std::size_t n) {
    if (size_ + n > capacity_) {
      std::size_t capacity = std::max<std::size_t>({size_ + n, capacity_ * 2, 256});
      std::unique_ptr<std::uint8_t[]> bigger(new std::uint8_t[capacity]);
      if (size_ > 0) std::memcpy(bigger.get(), data_.get(), size_);
      data_ = std::move(bigger);
      capacity_ = capacity;
    }
    std::uint8_t* at = data_.get() + size_;
    size_ += n;
    return at;
  }
  void reserve(std::size_t n) {
    std::size_t size = size_;
    grow(n > size ? n - size : 0);
    size_ = size;
  }

  template <typename T>
  void put(T value) {
    std::memcpy(grow(sizeof(T)), &value, sizeof(T));
  }
  void put_bytes(const void* bytes, std::size_t n) {
    if (n > 0) std::memcpy(grow(n), bytes, n);
  }
  void put_string(std::string_view text) {  // String: uint32 byte length, UTF-8 bytes
    put(static_cast<std::uint32_t>(text.size()));
    put_bytes(text.data(), text.size());
  }
  void put_string_map(const std::map<std::string, std::string>& map) {  // Map<string, string>
    std::size_t length_at = size_;
    put(std::uint32_t{0});
    for (const auto& [key, value] : map) {
      put_string(key);
      put_string(value);
    }
    patch(length_at, static_cast<std::uint32_t>(size_ - length_at - 4));
  }

  // A record is its opcode, its content's length, its content: begin_record() writes the first
  // two (a placeholder length) and returns where the record starts, end_record() fills in the
  // length once the content is written.
  std::size_t begin_record(std::uint8_t opcode) {
    std::size_t at = size_;
    put(opcode);
    put(std::uint64_t{0});
    return at;
  }
  void end_record(std::size_t record_at) {
    patch(record_at + 1, static_cast<std::uint64_t>(size_ - record_at - kRecordPrefix));
  }

  template <typename T>
  void patch(std::size_t at, T value) {
    std::memcpy(data_.get() + at, &value, sizeof(T));
  }

 private:
  std::unique_ptr<std::uint8_t[]> data_;
  std::size_t size_ = 0;
  std::size_t capacity_ = 0;
};

struct ZstdContextDeleter {
  void operator()(ZSTD_CCtx* context) const { ZSTD_freeCCtx(context); }
};

}  // namespace mcap_detail

using namespace mcap_detail;  // NOLINT(google-build-using-namespace): this file's own helpers

struct McapWriter::State {
  McapWriterOptions options;
  std::string path;
  std::FILE* file = nullptr;
  bool closed = false;
  std::optional<Error> failure;  // the first failed write; every later call returns it

  std::uint64_t position = 0;  // bytes written to the file
  std::uint32_t data_crc =
      core::crc32_init();  // over every byte written before the Data End record

  // The summary section's copies and indexes, serialized as they will be written.
  McapBuffer summary_schemas;
  McapBuffer summary_channels;
  McapBuffer chunk_indexes;
  McapBuffer attachment_indexes;
  McapBuffer metadata_indexes;
  std::uint16_t schema_count = 0;
  std::uint16_t channel_count = 0;
  McapStatistics statistics;

  // The chunk being filled: its Message records, uncompressed, their CRC so far (computed as
  // each record is appended, while its bytes are still in cache), the log time range, and per
  // channel the (log time, offset in `chunk`) of each message for the Message Index records.
  McapBuffer chunk;
  std::uint32_t chunk_crc = core::crc32_init();
  std::uint64_t chunk_messages = 0;
  std::uint64_t chunk_start_time = 0;
  std::uint64_t chunk_end_time = 0;
  std::vector<std::vector<std::pair<std::uint64_t, std::uint64_t>>> chunk_index_by_channel;
  std::vector<std::uint16_t> chunk_channels;  // channels with a message in the chunk

  McapBuffer scratch;     // records being written outside chunks
  McapBuffer compressed;  // the chunk's zstd frame
  std::unique_ptr<ZSTD_CCtx, ZstdContextDeleter> zstd;

  Status refuse_if_unusable(const char* function) const {
    if (failure) return *failure;
    if (closed) return Error{std::string("McapWriter::") + function + "(): the writer is closed"};
    return Status::Ok();
  }

  // Appends to the file; the first failure is kept and returned by every later call.
  Status emit(const std::uint8_t* bytes, std::size_t n, bool in_data_section = true) {
    if (failure) return *failure;
    if (n > 0 && std::fwrite(bytes, 1, n, file) != n) {
      failure = Error{"McapWriter: writing '" + path + "' failed: " + std::strerror(errno)};
      return *failure;
    }
    if (in_data_section) data_crc = core::crc32_update(data_crc, bytes, n);
    position += n;
    return Status::Ok();
  }
  Status emit(const McapBuffer& buffer, bool in_data_section = true) {
    return emit(buffer.data(), buffer.size(), in_data_section);
  }
  // Hands what stdio buffers to the operating system, so that a killed process loses nothing
  // written so far (a crash of the machine itself may still lose what the kernel has not
  // written back; fsync per chunk would cost a disk flush each).
  Status flush() {
    if (failure) return *failure;
    if (std::fflush(file) != 0) {
      failure = Error{"McapWriter: writing '" + path + "' failed: " + std::strerror(errno)};
      return *failure;
    }
    return Status::Ok();
  }

  Status write_chunk();
  Status write_summary_and_close();
};

bool McapWriterOptions::is_valid(std::string* error) const {
  auto fail = [error](std::string message) {
    if (error) *error = std::move(message);
    return false;
  };
  if (chunk_size == 0) return fail("McapWriterOptions: chunk_size must be positive");
  if (compression == McapCompression::kZstd &&
      (zstd_level < ZSTD_minCLevel() || zstd_level > ZSTD_maxCLevel())) {
    return fail("McapWriterOptions: zstd_level " + std::to_string(zstd_level) +
                " is outside zstd's range [" + std::to_string(ZSTD_minCLevel()) + ", " +
                std::to_string(ZSTD_maxCLevel()) + "]");
  }
  return true;
}

Result<McapWriter> McapWriter::open(const std::string& path, const McapWriterOptions& options) {
  std::string invalid;
  if (!options.is_valid(&invalid)) return Error{"McapWriter::open(): " + invalid};
  auto state = std::make_unique<State>();
  state->options = options;
  state->path = path;
  if (options.compression == McapCompression::kZstd) {
    state->zstd.reset(ZSTD_createCCtx());
    if (!state->zstd) return Error{"McapWriter::open(): zstd could not allocate its context"};
    ZSTD_CCtx_setParameter(state->zstd.get(), ZSTD_c_compressionLevel, options.zstd_level);
    // A reader checks each chunk with its CRC already; zstd's own checksum would be a third pass.
    ZSTD_CCtx_setParameter(state->zstd.get(), ZSTD_c_checksumFlag, 0);
  }
  state->file = std::fopen(path.c_str(), "wb");
  if (!state->file) {
    return Error{"McapWriter::open(): cannot create '" + path + "': " + std::strerror(errno)};
  }
  McapWriter writer(std::move(state));
  State& s = *writer.state_;
  s.chunk.reserve(options.chunk_size + options.chunk_size / 8);
  s.scratch.put_bytes(kMagic, sizeof(kMagic));
  std::size_t header = s.scratch.begin_record(kOpHeader);
  s.scratch.put_string(options.profile);
  s.scratch.put_string(options.library);
  s.scratch.end_record(header);
  Status written = s.emit(s.scratch);
  s.scratch.clear();
  if (!written) return written.error();
  return writer;
}

McapWriter::McapWriter(std::unique_ptr<State> state) : state_(std::move(state)) {}
McapWriter::McapWriter(McapWriter&&) noexcept = default;
McapWriter& McapWriter::operator=(McapWriter&& other) noexcept {
  if (this != &other) {
    finish();
    state_ = std::move(other.state_);
  }
  return *this;
}

McapWriter::~McapWriter() {
  finish();
}

void McapWriter::finish() noexcept {
  if (!state_) return;  // moved from
  if (!state_->closed) (void)close();
  if (state_->file) std::fclose(state_->file);  // close() failed before closing it
  state_->file = nullptr;
}

std::uint16_t McapWriter::add_schema(std::string_view name, std::string_view encoding,
                                     McapBytes data) {
  State& s = *state_;
  if (!s.refuse_if_unusable("add_schema")) return 0;
  assert(s.schema_count < std::numeric_limits<std::uint16_t>::max() && "too many schemas");
  const std::uint16_t id = ++s.schema_count;
  std::size_t record = s.summary_schemas.size();
  std::size_t at = s.summary_schemas.begin_record(kOpSchema);
  s.summary_schemas.put(id);
  s.summary_schemas.put_string(name);
  s.summary_schemas.put_string(encoding);
  s.summary_schemas.put(static_cast<std::uint32_t>(data.size()));
  s.summary_schemas.put_bytes(data.data(), data.size());
  s.summary_schemas.end_record(at);
  // The same bytes go to the data section now (before any channel that uses the schema) and
  // to the summary at close().
  if (!s.emit(s.summary_schemas.data() + record, s.summary_schemas.size() - record)) return 0;
  s.statistics.schema_count = s.schema_count;
  return id;
}

std::uint16_t McapWriter::add_channel(std::uint16_t schema_id, std::string_view topic,
                                      std::string_view message_encoding,
                                      const std::map<std::string, std::string>& metadata) {
  State& s = *state_;
  if (!s.refuse_if_unusable("add_channel")) return 0;
  assert(schema_id <= s.schema_count && "McapWriter::add_channel(): unknown schema id");
  assert(s.channel_count < std::numeric_limits<std::uint16_t>::max() && "too many channels");
  const std::uint16_t id = ++s.channel_count;
  std::size_t record = s.summary_channels.size();
  std::size_t at = s.summary_channels.begin_record(kOpChannel);
  s.summary_channels.put(id);
  s.summary_channels.put(schema_id);
  s.summary_channels.put_string(topic);
  s.summary_channels.put_string(message_encoding);
  s.summary_channels.put_string_map(metadata);
  s.summary_channels.end_record(at);
  if (!s.emit(s.summary_channels.data() + record, s.summary_channels.size() - record)) return 0;
  s.chunk_index_by_channel.emplace_back();
  s.statistics.channel_count = s.channel_count;
  s.statistics.channel_message_counts[id] = 0;
  return id;
}

Status McapWriter::write(std::uint16_t channel_id, std::uint32_t sequence,
                         std::uint64_t log_time_ns, std::uint64_t publish_time_ns, McapBytes data) {
  State& s = *state_;
  if (Status usable = s.refuse_if_unusable("write"); !usable) return usable;
  if (channel_id == 0 || channel_id > s.channel_count) {
    return Error{"McapWriter::write(): unknown channel id " + std::to_string(channel_id) + " (" +
                 (s.channel_count == 0
                      ? std::string("no channel was added")
                      : "add_channel() returned ids 1 to " + std::to_string(s.channel_count)) +
                 ")"};
  }
  const std::size_t offset = s.chunk.size();
  const std::size_t length = kRecordPrefix + kMessageFields + data.size();
  std::uint8_t* record = s.chunk.grow(length);
  const std::uint8_t opcode = kOpMessage;
  const std::uint64_t content_length = kMessageFields + data.size();
  std::memcpy(record, &opcode, 1);
  std::memcpy(record + 1, &content_length, 8);
  std::memcpy(record + 9, &channel_id, 2);
  std::memcpy(record + 11, &sequence, 4);
  std::memcpy(record + 15, &log_time_ns, 8);
  std::memcpy(record + 23, &publish_time_ns, 8);
  if (!data.empty()) std::memcpy(record + 31, data.data(), data.size());
  s.chunk_crc = core::crc32_update(s.chunk_crc, record, length);

  if (s.chunk_messages == 0) {
    s.chunk_start_time = s.chunk_end_time = log_time_ns;
  } else {
    s.chunk_start_time = std::min(s.chunk_start_time, log_time_ns);
    s.chunk_end_time = std::max(s.chunk_end_time, log_time_ns);
  }
  ++s.chunk_messages;
  auto& index = s.chunk_index_by_channel[channel_id - 1];
  if (index.empty()) s.chunk_channels.push_back(channel_id);
  index.emplace_back(log_time_ns, offset);

  McapStatistics& st = s.statistics;
  if (st.message_count == 0) {
    st.message_start_time = st.message_end_time = log_time_ns;
  } else {
    st.message_start_time = std::min(st.message_start_time, log_time_ns);
    st.message_end_time = std::max(st.message_end_time, log_time_ns);
  }
  ++st.message_count;
  ++st.channel_message_counts[channel_id];

  if (s.chunk.size() >= s.options.chunk_size) return s.write_chunk();
  return Status::Ok();
}

// The chunk record, then one Message Index record per channel in it, then a flush: from here
// on a reader of the file, even if the writer dies, has these messages.
Status McapWriter::State::write_chunk() {
  if (chunk_messages == 0) return Status::Ok();
  const std::uint8_t* records = chunk.data();
  std::size_t records_size = chunk.size();
  std::string_view compression;
  if (options.compression == McapCompression::kZstd) {
    compressed.clear();
    std::uint8_t* out = compressed.grow(ZSTD_compressBound(chunk.size()));
    std::size_t n = ZSTD_compress2(zstd.get(), out, compressed.size(), chunk.data(), chunk.size());
    if (ZSTD_isError(n)) {
      failure = Error{std::string("McapWriter: zstd failed to compress a chunk: ") +
                      ZSTD_getErrorName(n)};
      return *failure;
    }
    records = compressed.data();
    records_size = n;
    compression = "zstd";
  }

  const std::uint64_t chunk_start = position;
  scratch.clear();
  std::size_t at = scratch.begin_record(kOpChunk);
  scratch.put(chunk_start_time);
  scratch.put(chunk_end_time);
  scratch.put(static_cast<std::uint64_t>(chunk.size()));  // uncompressed_size
  scratch.put(core::crc32_final(chunk_crc));              // uncompressed_crc
  scratch.put_string(compression);
  scratch.put(static_cast<std::uint64_t>(records_size));  // the records' uint64 length prefix
  scratch.patch(at + 1, static_cast<std::uint64_t>(scratch.size() - kRecordPrefix + records_size));
  if (Status ok = emit(scratch); !ok) return ok;
  if (Status ok = emit(records, records_size); !ok) return ok;
  const std::uint64_t chunk_length = position - chunk_start;

  // Message Index records, by channel id so that a file's layout does not depend on the order
  // in which channels first spoke in a chunk.
  std::sort(chunk_channels.begin(), chunk_channels.end());
  const std::uint64_t indexes_start = position;
  std::vector<std::pair<std::uint16_t, std::uint64_t>> index_offsets;
  index_offsets.reserve(chunk_channels.size());
  scratch.clear();
  for (std::uint16_t channel : chunk_channels) {
    auto& entries = chunk_index_by_channel[channel - 1];
    index_offsets.emplace_back(channel, indexes_start + scratch.size());
    std::size_t index = scratch.begin_record(kOpMessageIndex);
    scratch.put(channel);
    scratch.put(static_cast<std::uint32_t>(entries.size() * 16));  // Array byte length
    for (const auto& [log_time, offset] : entries) {
      scratch.put(log_time);
      scratch.put(offset);
    }
    scratch.end_record(index);
    entries.clear();
  }
  if (Status ok = emit(scratch); !ok) return ok;
  const std::uint64_t indexes_length = position - indexes_start;

  std::size_t chunk_index = chunk_indexes.begin_record(kOpChunkIndex);
  chunk_indexes.put(chunk_start_time);
  chunk_indexes.put(chunk_end_time);
  chunk_indexes.put(chunk_start);
  chunk_indexes.put(chunk_length);
  chunk_indexes.put(static_cast<std::uint32_t>(index_offsets.size() * 10));  // Map byte length
  for (const auto& [channel, offset] : index_offsets) {
    chunk_indexes.put(channel);
    chunk_indexes.put(offset);
  }
  chunk_indexes.put(indexes_length);
  chunk_indexes.put_string(compression);
  chunk_indexes.put(static_cast<std::uint64_t>(records_size));  // compressed_size
  chunk_indexes.put(static_cast<std::uint64_t>(chunk.size()));  // uncompressed_size
  chunk_indexes.end_record(chunk_index);

  ++statistics.chunk_count;
  chunk.clear();
  chunk_crc = core::crc32_init();
  chunk_messages = 0;
  chunk_channels.clear();
  return flush();
}

Status McapWriter::attach(std::string_view name, std::string_view media_type,
                          std::uint64_t log_time_ns, std::uint64_t create_time_ns, McapBytes data) {
  State& s = *state_;
  if (Status usable = s.refuse_if_unusable("attach"); !usable) return usable;
  // The attachment's fields up to its data are built here; the data itself, which may be
  // large (meshes, images), is written from the caller's buffer.
  const std::uint64_t offset = s.position;
  s.scratch.clear();
  std::size_t at = s.scratch.begin_record(kOpAttachment);
  s.scratch.put(log_time_ns);
  s.scratch.put(create_time_ns);
  s.scratch.put_string(name);
  s.scratch.put_string(media_type);
  s.scratch.put(static_cast<std::uint64_t>(data.size()));
  const std::uint64_t content_length = s.scratch.size() - kRecordPrefix + data.size() + 4;
  s.scratch.patch(at + 1, content_length);
  // crc: of every field before it (the record's content, not its opcode and length)
  std::uint32_t crc = core::crc32_update(core::crc32_init(), s.scratch.data() + kRecordPrefix,
                                         s.scratch.size() - kRecordPrefix);
  crc = core::crc32_final(core::crc32_update(crc, data.data(), data.size()));
  if (Status ok = s.emit(s.scratch); !ok) return ok;
  if (Status ok = s.emit(data.data(), data.size()); !ok) return ok;
  if (Status ok = s.emit(reinterpret_cast<const std::uint8_t*>(&crc), 4); !ok) return ok;

  std::size_t index = s.attachment_indexes.begin_record(kOpAttachmentIndex);
  s.attachment_indexes.put(offset);
  s.attachment_indexes.put(kRecordPrefix + content_length);  // length, opcode and prefix included
  s.attachment_indexes.put(log_time_ns);
  s.attachment_indexes.put(create_time_ns);
  s.attachment_indexes.put(static_cast<std::uint64_t>(data.size()));
  s.attachment_indexes.put_string(name);
  s.attachment_indexes.put_string(media_type);
  s.attachment_indexes.end_record(index);
  ++s.statistics.attachment_count;
  return s.flush();
}

Status McapWriter::metadata(std::string_view name,
                            const std::map<std::string, std::string>& entries) {
  State& s = *state_;
  if (Status usable = s.refuse_if_unusable("metadata"); !usable) return usable;
  const std::uint64_t offset = s.position;
  s.scratch.clear();
  std::size_t at = s.scratch.begin_record(kOpMetadata);
  s.scratch.put_string(name);
  s.scratch.put_string_map(entries);
  s.scratch.end_record(at);
  if (Status ok = s.emit(s.scratch); !ok) return ok;

  std::size_t index = s.metadata_indexes.begin_record(kOpMetadataIndex);
  s.metadata_indexes.put(offset);
  s.metadata_indexes.put(static_cast<std::uint64_t>(s.scratch.size()));
  s.metadata_indexes.put_string(name);
  s.metadata_indexes.end_record(index);
  ++s.statistics.metadata_count;
  return s.flush();
}

Status McapWriter::close() {
  State& s = *state_;
  if (Status usable = s.refuse_if_unusable("close"); !usable) return usable;
  if (Status ok = s.write_chunk(); !ok) return ok;
  return s.write_summary_and_close();
}

// Data End, the summary (grouped by opcode, as the spec requires, Channels before Statistics),
// one Summary Offset per group, the Footer, the magic.
Status McapWriter::State::write_summary_and_close() {
  scratch.clear();
  std::size_t data_end = scratch.begin_record(kOpDataEnd);
  scratch.put(core::crc32_final(data_crc));
  scratch.end_record(data_end);
  if (Status ok = emit(scratch); !ok) return ok;

  McapBuffer statistics_record;
  std::size_t at = statistics_record.begin_record(kOpStatistics);
  statistics_record.put(statistics.message_count);
  statistics_record.put(statistics.schema_count);
  statistics_record.put(statistics.channel_count);
  statistics_record.put(statistics.attachment_count);
  statistics_record.put(statistics.metadata_count);
  statistics_record.put(statistics.chunk_count);
  statistics_record.put(statistics.message_start_time);
  statistics_record.put(statistics.message_end_time);
  statistics_record.put(static_cast<std::uint32_t>(statistics.channel_message_counts.size() * 10));
  for (const auto& [channel, count] : statistics.channel_message_counts) {
    statistics_record.put(channel);
    statistics_record.put(count);
  }
  statistics_record.end_record(at);

  const std::uint64_t summary_start = position;
  McapBuffer summary;
  McapBuffer offsets;
  auto add_group = [&](std::uint8_t opcode, const McapBuffer& group) {
    if (group.empty()) return;
    std::size_t record = offsets.begin_record(kOpSummaryOffset);
    offsets.put(opcode);
    offsets.put(static_cast<std::uint64_t>(summary_start + summary.size()));
    offsets.put(static_cast<std::uint64_t>(group.size()));
    offsets.end_record(record);
    summary.put_bytes(group.data(), group.size());
  };
  add_group(kOpSchema, summary_schemas);
  add_group(kOpChannel, summary_channels);
  add_group(kOpStatistics, statistics_record);
  add_group(kOpChunkIndex, chunk_indexes);
  add_group(kOpAttachmentIndex, attachment_indexes);
  add_group(kOpMetadataIndex, metadata_indexes);
  const std::uint64_t summary_offset_start = summary_start + summary.size();
  summary.put_bytes(offsets.data(), offsets.size());

  // summary_crc covers the summary and summary offset sections and the footer up to and
  // including summary_offset_start.
  summary.put(kOpFooter);
  summary.put(std::uint64_t{8 + 8 + 4});  // the length first: the CRC covers it
  summary.put(summary_start);
  summary.put(summary_offset_start);
  summary.put(core::crc32(summary.data(), summary.size()));
  summary.put_bytes(kMagic, sizeof(kMagic));
  if (Status ok = emit(summary, /*in_data_section=*/false); !ok) return ok;

  closed = true;
  const int closed_file = std::fclose(file);
  file = nullptr;
  if (closed_file != 0) {
    failure = Error{"McapWriter: writing '" + path + "' failed: " + std::strerror(errno)};
    return *failure;
  }
  return Status::Ok();
}

const McapStatistics& McapWriter::statistics() const {
  return state_->statistics;
}
std::uint64_t McapWriter::bytes_written() const {
  return state_->position;
}

}  // namespace telear::record
