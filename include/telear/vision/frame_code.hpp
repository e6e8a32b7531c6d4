#pragma once
// The frame code: a frame's number and capture time written into its picture, so that whoever
// shows the frame can read them back from the pixels and measure capture -> shown (glass to
// glass) without trusting any metadata path (docs/latency.md, where the layout is given for a
// camera filming a screen too).
//
// Layout. A strip of 34 x 4 blocks of 8 x 8 pixels (272 x 32 px), its top-left pixel at
//   x = 16,  y = floor((height - 48) / 16) * 16        (image order, top row first)
// i.e. 16 px from the left edge and at least 16 px above the bottom one, in the bottom-left
// corner where the simulated rigs show only the floor (never the arm or its marker) and clear
// of the AR view's 4 px status frame. The strip starts on a 16 px boundary and covers whole
// 16 x 16 JPEG macroblocks (4:2:0), so every 8 x 8 luma block of the code is one flat DCT
// block (its DC term alone: quantization moves it by a grey level or so at quality 50) and its
// chroma is neutral: JPEG keeps it down to low qualities. An image smaller than 304 x 64 has
// no room for it.
//
//   column 0       reference: white, black, white, black (top to bottom)
//   columns 1..32  data: column 1 + k holds nibble k of the 16 payload bytes (nibble 2j is
//                  byte j's high nibble), the top row its most significant bit
//   column 33      end: black, white, black, white
//
// A bit is a block: white (255, 255, 255) = 1, black (0, 0, 0) = 0. Payload, big-endian:
//   bytes 0..3    frame counter (the source's frame number, its low 32 bits)
//   bytes 4..11   capture time, ns on the source's monotonic clock (int64, two's complement)
//   bytes 12..15  CRC-32 (telear/core/crc32.hpp) of bytes 0..11
//
// Reading. Each block's luma (Y = (77 R + 150 G + 29 B) / 256) is taken over its inner 6 x 6
// pixels (a one-pixel shift, blur at the block edges and chroma bleeding from the neighbours
// do not reach it). The reference and end columns give the white and black levels; their
// difference (the contrast) must be at least 64 grey levels. A block is a bit when its inner
// pixels span less than half the contrast and its mean lies beyond a quarter of the contrast
// from the mid level; the reference and end columns must read as their patterns and the CRC
// must match. Anything else -- no code, a cropped, flipped or smeared block, a scaled or
// shifted strip -- reads as unreadable (nullopt), never as another frame's values: a wrong
// code passes only if it also carries a valid CRC-32 (every error of up to 6 bits is caught).

#include <cstdint>
#include <optional>

#include "telear/core/image.hpp"

namespace telear::vision {

struct FrameCode {
  std::uint32_t frame = 0;      // the source's frame number, modulo 2^32
  std::int64_t capture_ns = 0;  // the capture time on the source's clock (monotonic_ns there)

  bool operator==(const FrameCode&) const = default;
};

// The code's geometry, in pixels and blocks (see the layout above).
inline constexpr int kFrameCodeBlockPx = 8;
inline constexpr int kFrameCodeColumns = 34;  // reference, 32 data, end
inline constexpr int kFrameCodeRows = 4;
inline constexpr int kFrameCodeWidthPx = kFrameCodeColumns * kFrameCodeBlockPx;  // 272
inline constexpr int kFrameCodeHeightPx = kFrameCodeRows * kFrameCodeBlockPx;    // 32
inline constexpr int kFrameCodeMarginPx = 16;

// Where the code lies in an image: the strip's top-left pixel (image order) and its size.
struct FrameCodeRect {
  int x = 0, y = 0;
  int width = kFrameCodeWidthPx, height = kFrameCodeHeightPx;
};

// The strip's place in a width x height image; nullopt when the image is smaller than
// 304 x 64 (no room with the margins).
std::optional<FrameCodeRect> frame_code_rect(int width, int height);

// Writes `code` into `image` (RGB8 or RGBA8: alpha set opaque) at frame_code_rect(); false,
// the image untouched, when it has no room for the code or is neither.
bool write_frame_code(core::Image& image, const FrameCode& code);

// Reads the code at frame_code_rect() of `image` (RGB8 or RGBA8); nullopt: unreadable.
std::optional<FrameCode> read_frame_code(const core::Image& image);
// Reads the code whose strip starts at pixel (x, y) of `image` (e.g. an image holding the
// strip alone, read back from a frame buffer: x = y = 0); nullopt: unreadable, or the strip
// does not lie within the image.
std::optional<FrameCode> read_frame_code(const core::Image& image, int x, int y);

}  // namespace telear::vision
