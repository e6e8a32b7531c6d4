// The MCAP reader's reading side: messages in log-time order across chunks, attachments,
// metadata (include/telear/record/mcap_reader.hpp).

#include "mcap_reader_file.hpp"

namespace telear::record {
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
      const std::uint32_t crc = core::crc32(content->data(), crc_at);
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
