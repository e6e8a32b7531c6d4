// CRC-32 (telear/core/crc32.hpp): the catalogue's check value, the textbook bit-at-a-time
// definition on random data of every tail length, and the update over pieces (how the MCAP
// writer checksums a file being written).

#include "telear/core/crc32.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace telear::core {
namespace {

// A bit-at-a-time CRC-32, the textbook definition the table-driven one must agree with.
std::uint32_t crc32_bitwise(const std::uint8_t* p, std::size_t n) {
  std::uint32_t crc = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < n; ++i) {
    crc ^= p[i];
    for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

TEST(Crc32, MatchesTheCheckValueAndTheBitwiseDefinition) {
  EXPECT_EQ(crc32("123456789", 9), 0xCBF43926u);  // the CRC-32/ISO-HDLC check value
  EXPECT_EQ(crc32("", 0), 0u);
  std::mt19937 rng(7);
  std::vector<std::uint8_t> data(1000 + 3);  // not a multiple of 8: the tail loop runs too
  for (auto& b : data) b = static_cast<std::uint8_t>(rng());
  EXPECT_EQ(crc32(data.data(), data.size()), crc32_bitwise(data.data(), data.size()));
  for (std::size_t n = 0; n < 17; ++n) {  // every tail length, short buffers
    EXPECT_EQ(crc32(data.data(), n), crc32_bitwise(data.data(), n)) << n << " bytes";
  }
  // In pieces, as the MCAP writer checksums a file being written.
  std::uint32_t crc = crc32_init();
  crc = crc32_update(crc, data.data(), 5);
  crc = crc32_update(crc, data.data() + 5, 500);
  crc = crc32_update(crc, data.data() + 505, data.size() - 505);
  EXPECT_EQ(crc32_final(crc), crc32_bitwise(data.data(), data.size()));
}

}  // namespace
}  // namespace telear::core
