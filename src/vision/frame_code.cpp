#include "telear/vision/frame_code.hpp"

#include <algorithm>
#include <array>

#include "telear/core/crc32.hpp"

namespace telear::vision {
namespace {

constexpr int kPayloadBytes = 16;  // frame (4), capture time (8), CRC-32 (4)
constexpr int kDataColumns = kFrameCodeColumns - 2;
static_assert(kDataColumns * kFrameCodeRows == kPayloadBytes * 8, "one block per payload bit");

// The reference and end columns, top to bottom (1 = white).
constexpr std::array<int, kFrameCodeRows> kReferenceColumn = {1, 0, 1, 0};
constexpr std::array<int, kFrameCodeRows> kEndColumn = {0, 1, 0, 1};

// The smallest white - black difference of a readable code (grey levels). A block may span
// half of it inside and must keep a quarter of it from the mid level (see the header).
constexpr int kMinContrast = 64;

using Payload = std::array<std::uint8_t, kPayloadBytes>;

Payload encode_payload(const FrameCode& code) {
  Payload p{};
  for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>(code.frame >> (24 - 8 * i));
  const auto t = static_cast<std::uint64_t>(code.capture_ns);
  for (int i = 0; i < 8; ++i) p[4 + i] = static_cast<std::uint8_t>(t >> (56 - 8 * i));
  const std::uint32_t crc = core::crc32(p.data(), 12);
  for (int i = 0; i < 4; ++i) p[12 + i] = static_cast<std::uint8_t>(crc >> (24 - 8 * i));
  return p;
}

// Bit `row` (0 = top) of data column k: bit (3 - row) of nibble k.
int payload_bit(const Payload& p, int k, int row) {
  const int nibble = (k % 2 == 0) ? p[k / 2] >> 4 : p[k / 2] & 0x0F;
  return (nibble >> (3 - row)) & 1;
}

// 1 = white, 0 = black, for block (column, row) of the strip.
int block_value(const Payload& p, int column, int row) {
  if (column == 0) return kReferenceColumn[row];
  if (column == kFrameCodeColumns - 1) return kEndColumn[row];
  return payload_bit(p, column - 1, row);
}

struct BlockLuma {
  int mean = 0, min = 255, max = 0;
};

// Luma over the block's inner (block - 2) x (block - 2) pixels.
BlockLuma block_luma(const core::Image& image, int x0, int y0) {
  BlockLuma b;
  int sum = 0, n = 0;
  for (int y = y0 + 1; y < y0 + kFrameCodeBlockPx - 1; ++y) {
    const std::uint8_t* row = image.row(y);
    for (int x = x0 + 1; x < x0 + kFrameCodeBlockPx - 1; ++x) {
      const std::uint8_t* px = row + static_cast<std::size_t>(x) * image.channels;
      const int luma = (77 * px[0] + 150 * px[1] + 29 * px[2] + 128) >> 8;
      sum += luma;
      b.min = std::min(b.min, luma);
      b.max = std::max(b.max, luma);
      ++n;
    }
  }
  b.mean = (sum + n / 2) / n;
  return b;
}

}  // namespace

std::optional<FrameCodeRect> frame_code_rect(int width, int height) {
  const int m = kFrameCodeMarginPx;
  if (width < m + kFrameCodeWidthPx + m || height < m + kFrameCodeHeightPx + m) {
    return std::nullopt;
  }
  FrameCodeRect rect;
  rect.x = m;
  rect.y = (height - m - kFrameCodeHeightPx) / 16 * 16;  // on the JPEG macroblock grid
  return rect;
}

bool write_frame_code(core::Image& image, const FrameCode& code) {
  const auto rect = frame_code_rect(image.width, image.height);
  if (!rect || (image.channels != 3 && image.channels != 4) ||
      image.pixels.size() != image.row_bytes() * static_cast<std::size_t>(image.height)) {
    return false;
  }
  const Payload payload = encode_payload(code);
  for (int row = 0; row < kFrameCodeRows; ++row) {
    for (int column = 0; column < kFrameCodeColumns; ++column) {
      const std::uint8_t level = block_value(payload, column, row) ? 255 : 0;
      const int x0 = rect->x + column * kFrameCodeBlockPx;
      const int y0 = rect->y + row * kFrameCodeBlockPx;
      for (int y = y0; y < y0 + kFrameCodeBlockPx; ++y) {
        std::uint8_t* px = image.row(y) + static_cast<std::size_t>(x0) * image.channels;
        for (int x = 0; x < kFrameCodeBlockPx; ++x, px += image.channels) {
          px[0] = px[1] = px[2] = level;
          if (image.channels == 4) px[3] = 255;
        }
      }
    }
  }
  return true;
}

std::optional<FrameCode> read_frame_code(const core::Image& image) {
  const auto rect = frame_code_rect(image.width, image.height);
  if (!rect) return std::nullopt;
  return read_frame_code(image, rect->x, rect->y);
}

std::optional<FrameCode> read_frame_code(const core::Image& image, int x, int y) {
  if ((image.channels != 3 && image.channels != 4) || x < 0 || y < 0 ||
      x + kFrameCodeWidthPx > image.width || y + kFrameCodeHeightPx > image.height ||
      image.pixels.size() != image.row_bytes() * static_cast<std::size_t>(image.height)) {
    return std::nullopt;
  }
  std::array<std::array<BlockLuma, kFrameCodeColumns>, kFrameCodeRows> blocks;
  for (int row = 0; row < kFrameCodeRows; ++row) {
    for (int column = 0; column < kFrameCodeColumns; ++column) {
      blocks[row][column] =
          block_luma(image, x + column * kFrameCodeBlockPx, y + row * kFrameCodeBlockPx);
    }
  }
  // The white and black levels from the reference and end columns (four blocks each).
  int white = 0, black = 0;
  for (int row = 0; row < kFrameCodeRows; ++row) {
    for (int column : {0, kFrameCodeColumns - 1}) {
      const bool is_white = (column == 0 ? kReferenceColumn : kEndColumn)[row] == 1;
      (is_white ? white : black) += blocks[row][column].mean;
    }
  }
  white /= kFrameCodeRows;
  black /= kFrameCodeRows;
  const int contrast = white - black;
  if (contrast < kMinContrast) return std::nullopt;
  const int mid = (white + black) / 2;
  const int margin = contrast / 4;

  Payload payload{};
  for (int row = 0; row < kFrameCodeRows; ++row) {
    for (int column = 0; column < kFrameCodeColumns; ++column) {
      const BlockLuma& b = blocks[row][column];
      if (b.max - b.min > contrast / 2) return std::nullopt;  // not one flat block
      int bit = 0;
      if (b.mean >= mid + margin) {
        bit = 1;
      } else if (b.mean > mid - margin) {
        return std::nullopt;  // neither white nor black
      }
      if (column == 0 || column == kFrameCodeColumns - 1) {
        if (bit != block_value(payload, column, row)) return std::nullopt;
        continue;
      }
      const int k = column - 1;
      const int shift = (k % 2 == 0 ? 4 : 0) + (3 - row);
      payload[k / 2] = static_cast<std::uint8_t>(payload[k / 2] | (bit << shift));
    }
  }
  std::uint32_t crc = 0;
  for (int i = 0; i < 4; ++i) crc = (crc << 8) | payload[12 + i];
  if (crc != core::crc32(payload.data(), 12)) return std::nullopt;
  FrameCode code;
  for (int i = 0; i < 4; ++i) code.frame = (code.frame << 8) | payload[i];
  std::uint64_t t = 0;
  for (int i = 0; i < 8; ++i) t = (t << 8) | payload[4 + i];
  code.capture_ns = static_cast<std::int64_t>(t);
  return code;
}

}  // namespace telear::vision
