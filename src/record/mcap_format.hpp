#pragma once
// Internal to record: the MCAP format's constants (https://mcap.dev/spec), which the writer and
// the reader share: the record opcodes, the magic, the sizes of fixed fields.

#include <cstddef>
#include <cstdint>

namespace telear::record::mcap_format {

// Record opcodes (https://mcap.dev/spec#records).
enum Opcode : std::uint8_t {
  kOpHeader = 0x01,
  kOpFooter = 0x02,
  kOpSchema = 0x03,
  kOpChannel = 0x04,
  kOpMessage = 0x05,
  kOpChunk = 0x06,
  kOpMessageIndex = 0x07,
  kOpChunkIndex = 0x08,
  kOpAttachment = 0x09,
  kOpAttachmentIndex = 0x0A,
  kOpStatistics = 0x0B,
  kOpMetadata = 0x0C,
  kOpMetadataIndex = 0x0D,
  kOpSummaryOffset = 0x0E,
  kOpDataEnd = 0x0F,
};

// The file's first and last eight bytes.
inline constexpr std::uint8_t kMagic[8] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
// A record's opcode and uint64 content length.
inline constexpr std::size_t kRecordPrefix = 1 + 8;
// A Message record's channel_id, sequence, log_time, publish_time.
inline constexpr std::size_t kMessageFields = 2 + 4 + 8 + 8;

}  // namespace telear::record::mcap_format
