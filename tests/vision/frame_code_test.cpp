// The frame code (telear/vision/frame_code.hpp): exact through the stream's JPEG (TurboJPEG, as
// the vision server encodes) at quality 85 and down to 50 with a noisy picture around it;
// unreadable -- never another value -- when a block is flipped, the strip cropped, the code
// absent, or under thousands of seeded random corruptions.

#include "telear/vision/frame_code.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <random>
#include <unordered_set>
#include <vector>

#include "telear/core/crc32.hpp"

#include "telear/net/jpeg_codec.hpp"

namespace telear::vision {
namespace {

// A camera-like picture: colour gradients and per-pixel noise of +-`noise` grey levels.
core::Image noisy_image(int width, int height, int noise, std::uint64_t seed) {
  core::Image image(width, height, 3);
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> n(-noise, noise);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const int base[3] = {255 * x / width, 255 * y / height, (x / 24 + y / 24) % 2 ? 200 : 50};
      for (int c = 0; c < 3; ++c)
        image.at(x, y, c) = static_cast<std::uint8_t>(std::clamp(base[c] + n(rng), 0, 255));
    }
  }
  return image;
}

core::Image through_jpeg(const core::Image& image, int quality) {
  net::JpegEncoder encoder;
  net::JpegDecoder decoder;
  auto jpeg = encoder.encode(image, quality);
  EXPECT_TRUE(jpeg) << jpeg.error().message;
  auto decoded = decoder.decode(*jpeg);
  EXPECT_TRUE(decoded) << decoded.error().message;
  return *decoded;
}

// Sets block (column, row) of the code in `image` to `level` (all three channels).
void fill_block(core::Image& image, int column, int row, std::uint8_t level) {
  const FrameCodeRect rect = frame_code_rect(image.width, image.height).value();
  for (int y = 0; y < kFrameCodeBlockPx; ++y) {
    for (int x = 0; x < kFrameCodeBlockPx; ++x) {
      for (int c = 0; c < 3; ++c) {
        image.at(rect.x + column * kFrameCodeBlockPx + x, rect.y + row * kFrameCodeBlockPx + y, c) =
            level;
      }
    }
  }
}

// Turns block (column, row) white <-> black.
void flip_block(core::Image& image, int column, int row) {
  const FrameCodeRect rect = frame_code_rect(image.width, image.height).value();
  const std::uint8_t was =
      image.at(rect.x + column * kFrameCodeBlockPx + 3, rect.y + row * kFrameCodeBlockPx + 3, 0);
  fill_block(image, column, row, was > 127 ? 0 : 255);
}

const FrameCode kCode{0x89ABCDEFu, 0x0123456789ABCDEFll};

TEST(FrameCode, LiesInTheBottomLeftCornerOnTheMacroblockGrid) {
  ASSERT_TRUE(frame_code_rect(640, 480));
  EXPECT_EQ(frame_code_rect(640, 480)->x, 16);
  EXPECT_EQ(frame_code_rect(640, 480)->y, 432);  // 480 - 16 - 32
  EXPECT_EQ(frame_code_rect(1280, 720)->y, 672);
  EXPECT_EQ(frame_code_rect(650, 487)->y, 432);  // floor((487 - 48) / 16) * 16
  EXPECT_EQ(frame_code_rect(640, 480)->width, 272);
  EXPECT_EQ(frame_code_rect(640, 480)->height, 32);
  EXPECT_TRUE(frame_code_rect(304, 64));
  EXPECT_FALSE(frame_code_rect(303, 480));  // no room with the margins
  EXPECT_FALSE(frame_code_rect(640, 63));
  core::Image small(160, 120, 3);
  EXPECT_FALSE(write_frame_code(small, kCode));
  EXPECT_EQ(small.pixels, core::Image(160, 120, 3).pixels) << "left untouched";
  core::Image grey(640, 480, 1);
  EXPECT_FALSE(write_frame_code(grey, kCode));
}

TEST(FrameCode, ReadsBackExactlyIncludingTheExtremeValues) {
  core::Image image = noisy_image(640, 480, 30, 1);
  for (const FrameCode& code :
       {kCode, FrameCode{0, 0}, FrameCode{std::numeric_limits<std::uint32_t>::max(), -1},
        FrameCode{1, std::numeric_limits<std::int64_t>::min()},
        FrameCode{2, std::numeric_limits<std::int64_t>::max()}}) {
    ASSERT_TRUE(write_frame_code(image, code));
    EXPECT_EQ(read_frame_code(image), code);
  }
  // RGBA, as a frame buffer is read back; and the strip alone, at (0, 0).
  core::Image rgba(640, 480, 4);
  ASSERT_TRUE(write_frame_code(rgba, kCode));
  EXPECT_EQ(read_frame_code(rgba), kCode);
  const FrameCodeRect rect = *frame_code_rect(640, 480);
  core::Image strip(rect.width, rect.height, 3);
  for (int y = 0; y < rect.height; ++y) {
    std::copy_n(image.row(rect.y + y) + rect.x * 3, rect.width * 3, strip.row(y));
  }
  EXPECT_EQ(read_frame_code(strip, 0, 0), FrameCode({2, std::numeric_limits<std::int64_t>::max()}));
}

TEST(FrameCode, SurvivesTheStreamsJpegAtQuality85AndDownTo50) {
  struct Case {
    int width, height, quality;
  };
  for (const Case c : {Case{640, 480, 85}, Case{640, 480, 50}, Case{1280, 720, 85},
                       Case{650, 487, 50}, Case{320, 240, 70}}) {
    core::Image image = noisy_image(c.width, c.height, 40, 2);
    const FrameCode code{static_cast<std::uint32_t>(c.width * 7 + c.quality),
                         987654321012345 + c.height};
    ASSERT_TRUE(write_frame_code(image, code));
    EXPECT_EQ(read_frame_code(through_jpeg(image, c.quality)), code)
        << c.width << "x" << c.height << " at quality " << c.quality;
  }
}

TEST(FrameCode, ReadsThroughModerateNoiseOnTheCodeItself) {
  core::Image image = noisy_image(640, 480, 10, 3);
  ASSERT_TRUE(write_frame_code(image, kCode));
  std::mt19937_64 rng(4);
  std::normal_distribution<double> noise(0.0, 12.0);  // a camera's sensor noise, and more
  for (auto& p : image.pixels)
    p = static_cast<std::uint8_t>(std::clamp(p + noise(rng), 0.0, 255.0));
  EXPECT_EQ(read_frame_code(through_jpeg(image, 85)), kCode);
}

TEST(FrameCode, AnyFlippedBlockIsUnreadable) {
  core::Image image = noisy_image(320, 64, 20, 5);
  ASSERT_TRUE(write_frame_code(image, kCode));
  ASSERT_EQ(read_frame_code(image), kCode);
  for (int column = 0; column < kFrameCodeColumns; ++column) {
    for (int row = 0; row < kFrameCodeRows; ++row) {
      core::Image flipped = image;
      flip_block(flipped, column, row);
      EXPECT_EQ(read_frame_code(flipped), std::nullopt) << "block " << column << ", " << row;
    }
  }
}

TEST(FrameCode, EveryPairOfFlippedDataBlocksIsUnreadable) {
  core::Image image = noisy_image(320, 64, 20, 6);
  ASSERT_TRUE(write_frame_code(image, kCode));
  const int bits = (kFrameCodeColumns - 2) * kFrameCodeRows;
  int unreadable = 0;
  for (int a = 0; a < bits; ++a) {
    core::Image once = image;
    flip_block(once, 1 + a / kFrameCodeRows, a % kFrameCodeRows);
    for (int b = a + 1; b < bits; ++b) {
      core::Image twice = once;
      flip_block(twice, 1 + b / kFrameCodeRows, b % kFrameCodeRows);
      unreadable += !read_frame_code(twice).has_value();
    }
  }
  EXPECT_EQ(unreadable, bits * (bits - 1) / 2);
}

TEST(FrameCode, ACroppedStripIsUnreadable) {
  core::Image image = noisy_image(640, 480, 20, 7);
  ASSERT_TRUE(write_frame_code(image, kCode));
  // The end column painted over (what cropping the picture short of it leaves).
  core::Image cut = image;
  for (int row = 0; row < kFrameCodeRows; ++row) fill_block(cut, kFrameCodeColumns - 1, row, 128);
  EXPECT_EQ(read_frame_code(cut), std::nullopt);
  // The strip alone, one pixel short; and a strip that does not lie within the image.
  const FrameCodeRect rect = *frame_code_rect(640, 480);
  core::Image strip(rect.width - 1, rect.height, 3);
  for (int y = 0; y < rect.height; ++y) {
    std::copy_n(image.row(rect.y + y) + rect.x * 3, strip.width * 3, strip.row(y));
  }
  EXPECT_EQ(read_frame_code(strip, 0, 0), std::nullopt);
  EXPECT_EQ(read_frame_code(image, 640 - 271, rect.y), std::nullopt);
  EXPECT_EQ(read_frame_code(image, -1, rect.y), std::nullopt);
  // The picture cropped by 16 px on the left: the strip now starts at x = 0.
  core::Image cropped(624, 480, 3);
  for (int y = 0; y < 480; ++y) std::copy_n(image.row(y) + 16 * 3, 624 * 3, cropped.row(y));
  EXPECT_EQ(read_frame_code(cropped), std::nullopt);
}

TEST(FrameCode, AFrameWithoutACodeIsUnreadable) {
  EXPECT_EQ(read_frame_code(noisy_image(640, 480, 40, 8)), std::nullopt);
  for (std::uint8_t level : {0, 128, 255}) {
    core::Image flat(640, 480, 3);
    std::fill(flat.pixels.begin(), flat.pixels.end(), level);
    EXPECT_EQ(read_frame_code(flat), std::nullopt) << int(level);
  }
  // An 8 px checkerboard on the code's grid passes both reference columns (white-black-white-
  // black in column 0, the opposite in column 33): only the CRC tells it from a code.
  core::Image checker(640, 480, 3);
  const FrameCodeRect rect = *frame_code_rect(640, 480);
  for (int y = 0; y < 480; ++y) {
    for (int x = 0; x < 640; ++x) {
      const bool white = (((x - rect.x) / 8) + ((y - rect.y) / 8)) % 2 == 0;
      for (int c = 0; c < 3; ++c) checker.at(x, y, c) = white ? 255 : 0;
    }
  }
  EXPECT_EQ(read_frame_code(checker), std::nullopt);
}

// The payload's 96 bits and their CRC-32 form a code of Hamming distance 7: no error of 1 to 6
// bits (blocks) leaves the CRC valid. CRC-32 is affine, crc(m ^ e) = crc(m) ^ L(e), so an error
// e passes exactly when the XOR of its bits' syndromes (L of each data bit, a unit vector for
// each CRC bit) is zero; checked for every set of up to 6 of the 128 bits by meeting sums of up
// to 3 syndromes.
TEST(FrameCode, TheChecksumCatchesEveryErrorOfUpToSixBits) {
  constexpr int kDataBits = 96;
  std::array<std::uint8_t, kDataBits / 8> zero{};
  const std::uint32_t crc_zero = core::crc32(zero.data(), zero.size());
  std::vector<std::uint32_t> syndrome;
  for (int i = 0; i < kDataBits; ++i) {
    std::array<std::uint8_t, kDataBits / 8> bit{};
    bit[i / 8] = static_cast<std::uint8_t>(0x80 >> (i % 8));
    syndrome.push_back(core::crc32(bit.data(), bit.size()) ^ crc_zero);
  }
  for (int j = 0; j < 32; ++j) syndrome.push_back(1u << j);
  const int n = static_cast<int>(syndrome.size());
  // The sums of every 1, 2 and 3 distinct syndromes: a set of up to 6 bits with a zero sum
  // splits into two such sets of equal sums (or is one, summing to zero), and two different
  // sets of equal sums give a zero sum over the bits in one but not both (1 to 6 of them).
  std::unordered_set<std::uint32_t> sums;
  bool zero_sum = false;
  auto add = [&](std::uint32_t sum) { zero_sum |= sum == 0 || !sums.insert(sum).second; };
  for (int a = 0; a < n; ++a) {
    add(syndrome[a]);
    for (int b = a + 1; b < n; ++b) {
      add(syndrome[a] ^ syndrome[b]);
      for (int c = b + 1; c < n; ++c) add(syndrome[a] ^ syndrome[b] ^ syndrome[c]);
    }
  }
  EXPECT_FALSE(zero_sum);
  EXPECT_EQ(sums.size(), std::size_t{128 + 128 * 127 / 2 + 128 * 127 * 126 / 6});
}

// Thousands of seeded corruptions of a stamped frame -- flipped, grey or noisy blocks, noise
// over rectangles, the strip shifted, JPEG at a random quality, combinations -- read either as
// the code or as unreadable, never as another value.
TEST(FrameCode, NeverAWrongValueUnderRandomCorruption) {
  std::mt19937_64 rng(11);
  auto uniform = [&rng](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  const core::Image clean = noisy_image(320, 64, 30, 9);
  int wrong = 0, exact = 0, unreadable = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const FrameCode code{static_cast<std::uint32_t>(rng()), static_cast<std::int64_t>(rng())};
    core::Image image = clean;
    ASSERT_TRUE(write_frame_code(image, code));
    const FrameCodeRect rect = *frame_code_rect(image.width, image.height);
    const int kinds = uniform(1, 3);
    for (int k = 0; k < kinds; ++k) {
      switch (uniform(0, 5)) {
        case 0:  // flip up to 12 blocks
          for (int n = uniform(1, 12); n > 0; --n) {
            flip_block(image, uniform(0, kFrameCodeColumns - 1), uniform(0, kFrameCodeRows - 1));
          }
          break;
        case 1:  // a block set to any grey
          fill_block(image, uniform(0, kFrameCodeColumns - 1), uniform(0, kFrameCodeRows - 1),
                     static_cast<std::uint8_t>(uniform(0, 255)));
          break;
        case 2: {  // noise over a rectangle of the strip
          const int x0 = rect.x + uniform(0, rect.width - 1),
                    y0 = rect.y + uniform(0, rect.height - 1);
          const int x1 = std::min(image.width, x0 + uniform(1, 40));
          const int y1 = std::min(image.height, y0 + uniform(1, 20));
          for (int y = y0; y < y1; ++y) {
            for (int x = x0; x < x1; ++x) {
              for (int c = 0; c < 3; ++c) image.at(x, y, c) = static_cast<std::uint8_t>(rng());
            }
          }
          break;
        }
        case 3: {  // the whole picture shifted by up to 5 px
          const int dx = uniform(-5, 5), dy = uniform(-5, 5);
          core::Image shifted = image;
          for (int y = 0; y < image.height; ++y) {
            for (int x = 0; x < image.width; ++x) {
              const int sx = std::clamp(x - dx, 0, image.width - 1);
              const int sy = std::clamp(y - dy, 0, image.height - 1);
              for (int c = 0; c < 3; ++c) shifted.at(x, y, c) = image.at(sx, sy, c);
            }
          }
          image = shifted;
          break;
        }
        case 4:  // JPEG at a random quality
          image = through_jpeg(image, uniform(10, 95));
          break;
        default: {  // two data columns swapped
          const int a = uniform(1, kFrameCodeColumns - 2), b = uniform(1, kFrameCodeColumns - 2);
          for (int y = rect.y; y < rect.y + rect.height; ++y) {
            for (int x = 0; x < kFrameCodeBlockPx * 3; ++x) {
              std::swap(image.row(y)[(rect.x + a * kFrameCodeBlockPx) * 3 + x],
                        image.row(y)[(rect.x + b * kFrameCodeBlockPx) * 3 + x]);
            }
          }
        }
      }
    }
    const auto read = read_frame_code(image);
    if (!read) {
      ++unreadable;
    } else if (*read == code) {
      ++exact;
    } else {
      ++wrong;
    }
  }
  EXPECT_EQ(wrong, 0);
  // Both outcomes occur: the corruptions are neither all harmless nor all fatal.
  EXPECT_GT(exact, 100) << unreadable << " unreadable";
  EXPECT_GT(unreadable, 500) << exact << " exact";
  RecordProperty("exact", exact);
  RecordProperty("unreadable", unreadable);
}

}  // namespace
}  // namespace telear::vision
