#include "telear/record/mcap_reader.hpp"

#include "mcap_reader_file.hpp"

namespace telear::record {
namespace mcap_reader_detail {

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
    const std::uint32_t crc = core::crc32(out.data(), out.size());
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
    std::uint32_t crc = core::crc32_update(core::crc32_init(), summary.data(), summary.size());
    crc = core::crc32_final(core::crc32_update(crc, footer.data(), kPrefix + 16));
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
}  // namespace telear::record
