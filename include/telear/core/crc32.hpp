#pragma once
// CRC-32 (the IEEE 802.3 / zlib polynomial 0x04C11DB7, reflected, initial and final XOR
// 0xFFFFFFFF; "CRC-32/ISO-HDLC"): crc32_final(crc32_update(crc32_init(), bytes)) of "123456789"
// is 0xCBF43926. The one implementation of the checksum MCAP files carry
// (telear/record/mcap_writer.hpp) and the frame code protects its payload with
// (telear/vision/frame_code.hpp). The update runs over several buffers, as a file is written
// piece by piece.

#include <cstddef>
#include <cstdint>

namespace telear::core {

constexpr std::uint32_t crc32_init() {
  return 0xFFFFFFFFu;
}
std::uint32_t crc32_update(std::uint32_t crc, const void* data, std::size_t size);
constexpr std::uint32_t crc32_final(std::uint32_t crc) {
  return crc ^ 0xFFFFFFFFu;
}

inline std::uint32_t crc32(const void* data, std::size_t size) {
  return crc32_final(crc32_update(crc32_init(), data, size));
}

}  // namespace telear::core
