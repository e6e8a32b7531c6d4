#include "telear/net/jpeg_codec.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <turbojpeg.h>

#include <cmath>

#include "telear/net/stereo_jpeg_decoder.hpp"

namespace telear::net {
namespace {

using ::testing::HasSubstr;

// A smooth gradient with a square: JPEG's easy case, so q95 must come back close.
core::Image test_image(int width, int height) {
  core::Image image(width, height, 3);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const bool square = x > width / 4 && x < width / 2 && y > height / 4 && y < height / 2;
      image.at(x, y, 0) = static_cast<std::uint8_t>(255 * x / width);
      image.at(x, y, 1) = static_cast<std::uint8_t>(255 * y / height);
      image.at(x, y, 2) = square ? 220 : 40;
    }
  }
  return image;
}

double mean_abs_diff(const core::Image& a, const core::Image& b) {
  double sum = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) sum += std::abs(a.pixels[i] - b.pixels[i]);
  return sum / static_cast<double>(a.pixels.size());
}

TEST(JpegCodec, RoundTripKeepsSizeAndContent) {
  const core::Image image = test_image(160, 120);
  JpegEncoder encoder;
  JpegDecoder decoder;
  auto jpeg = encoder.encode(image, 95);
  ASSERT_TRUE(jpeg) << jpeg.error().message;
  EXPECT_EQ(static_cast<unsigned char>((*jpeg)[0]), 0xFF);  // SOI marker
  EXPECT_EQ(static_cast<unsigned char>((*jpeg)[1]), 0xD8);
  EXPECT_LT(jpeg->size(), image.pixels.size());
  auto decoded = decoder.decode(*jpeg);
  ASSERT_TRUE(decoded) << decoded.error().message;
  EXPECT_EQ(decoded->width, 160);
  EXPECT_EQ(decoded->height, 120);
  EXPECT_EQ(decoded->channels, 3);
  EXPECT_LT(mean_abs_diff(image, *decoded), 3.0);
}

TEST(JpegCodec, LowerQualityIsSmaller) {
  const core::Image image = test_image(320, 240);
  JpegEncoder encoder;
  auto high = encoder.encode(image, 95);
  auto low = encoder.encode(image, 20);
  ASSERT_TRUE(high && low);
  EXPECT_LT(low->size(), high->size());
}

TEST(JpegCodec, EncodeRejectsBadQualityAndImages) {
  JpegEncoder encoder;
  auto bad_quality = encoder.encode(test_image(32, 32), 0);
  ASSERT_FALSE(bad_quality);
  EXPECT_THAT(bad_quality.error().message, HasSubstr("quality 0 is outside 1..100"));
  auto grey = encoder.encode(core::Image(32, 32, 1), 80);
  ASSERT_FALSE(grey);
  EXPECT_THAT(grey.error().message, HasSubstr("expected a non-empty RGB8 image, got 32x32x1"));
}

TEST(JpegCodec, DecodeRejectsGarbageWithAMessage) {
  JpegDecoder decoder;
  auto empty = decoder.decode("");
  ASSERT_FALSE(empty);
  EXPECT_THAT(empty.error().message, HasSubstr("no data"));
  auto garbage = decoder.decode("this is not a JPEG at all, just text");
  ASSERT_FALSE(garbage);
  EXPECT_THAT(garbage.error().message, HasSubstr("JPEG decode: not a readable JPEG header"));
}

TEST(JpegCodec, DecodeRejectsTruncatedAndCorruptData) {
  JpegEncoder encoder;
  JpegDecoder decoder;
  auto jpeg = encoder.encode(test_image(160, 120), 90);
  ASSERT_TRUE(jpeg);
  const std::string truncated = jpeg->substr(0, jpeg->size() / 2);
  auto cut = decoder.decode(truncated);
  ASSERT_FALSE(cut);
  EXPECT_THAT(cut.error().message, HasSubstr("JPEG decode: corrupt 160x120 image"));

  // Bytes flipped in the entropy-coded data (after the headers): never a crash, either an
  // error or an image of the header's size.
  std::string flipped = *jpeg;
  for (std::size_t i = flipped.size() / 2; i + 2 < flipped.size(); i += 17) flipped[i] ^= 0x5A;
  auto corrupt = decoder.decode(flipped);
  if (corrupt) {
    EXPECT_EQ(corrupt->width, 160);
    EXPECT_EQ(corrupt->height, 120);
  } else {
    EXPECT_THAT(corrupt.error().message, HasSubstr("JPEG decode"));
  }
  // The decoder is still usable after a failure.
  EXPECT_TRUE(decoder.decode(*jpeg));
}

TEST(JpegCodec, DecodeRefusesImagesBeyondThePixelLimit) {
  JpegEncoder encoder;
  JpegDecoder decoder;
  auto jpeg = encoder.encode(test_image(160, 120), 80);
  ASSERT_TRUE(jpeg);
  auto refused = decoder.decode(*jpeg, 100 * 100);
  ASSERT_FALSE(refused);
  EXPECT_THAT(refused.error().message,
              HasSubstr("image size 160x120 is beyond the limit of 10000 pixels"));
}

// Issue 23: both eyes at once give what decoding them in turn gives, over many pairs (one
// worker, reused), and a corrupt eye is named.
TEST(StereoJpegDecoder, DecodesBothEyesAsOneDecoderWouldAndNamesACorruptEye) {
  JpegEncoder encoder;
  JpegDecoder reference;
  StereoJpegDecoder pair_decoder;
  for (int i = 0; i < 20; ++i) {
    core::Image left = test_image(160 + 8 * i, 120);
    core::Image right = test_image(96, 64 + 8 * i);
    auto left_jpeg = encoder.encode(left, 85);
    auto right_jpeg = encoder.encode(right, 85);
    ASSERT_TRUE(left_jpeg && right_jpeg);
    auto pair = pair_decoder.decode(*left_jpeg, *right_jpeg);
    ASSERT_TRUE(pair) << pair.error().message;
    EXPECT_EQ(pair->left.pixels, reference.decode(*left_jpeg)->pixels);
    EXPECT_EQ(pair->right.pixels, reference.decode(*right_jpeg)->pixels);
    EXPECT_EQ(pair->right.width, 96);
  }
  auto good = encoder.encode(test_image(64, 48), 85);
  ASSERT_TRUE(good);
  auto bad_left = pair_decoder.decode("not a jpeg", *good);
  ASSERT_FALSE(bad_left);
  EXPECT_THAT(bad_left.error().message, ::testing::StartsWith("left eye: "));
  auto bad_right = pair_decoder.decode(*good, "");
  ASSERT_FALSE(bad_right);
  EXPECT_THAT(bad_right.error().message, ::testing::StartsWith("right eye: "));
  EXPECT_TRUE(pair_decoder.decode(*good, *good));  // still working after the errors
}

// Issue 23: the planes without the colour conversion. Converted by to_rgb (the GPU shader's
// arithmetic on the CPU) they are the RGB decode to within libjpeg's own rounding; a grey JPEG
// has neutral chroma; bad data gets decode()'s errors.
TEST(JpegCodec, DecodePlanesGivesTheImageBeforeItsColourConversion) {
  const core::Image image = test_image(161, 121);  // odd: the chroma planes round up
  JpegEncoder encoder;
  JpegDecoder decoder;
  auto jpeg = encoder.encode(image, 85);
  ASSERT_TRUE(jpeg) << jpeg.error().message;
  auto planes = decoder.decode_planes(*jpeg);
  ASSERT_TRUE(planes) << planes.error().message;
  EXPECT_EQ(planes->width, 161);
  EXPECT_EQ(planes->height, 121);
  EXPECT_EQ(planes->chroma_width, 81);  // 4:2:0
  EXPECT_EQ(planes->chroma_height, 61);
  ASSERT_EQ(planes->y.size(), 161u * 121u);
  ASSERT_EQ(planes->cb.size(), 81u * 61u);
  const core::Image rgb = core::to_rgb(*planes);
  const core::Image reference = *decoder.decode(*jpeg);
  ASSERT_EQ(rgb.pixels.size(), reference.pixels.size());
  int worst = 0;
  for (std::size_t i = 0; i < rgb.pixels.size(); ++i) {
    worst = std::max(worst, std::abs(rgb.pixels[i] - reference.pixels[i]));
  }
  EXPECT_LT(mean_abs_diff(rgb, reference), 0.5);
  EXPECT_LE(worst, 8);  // at the square's edges, where the upsampling filters differ most
  // Luma is the grey image marker detection wants: BT.601 of the decoded RGB.
  const std::size_t centre = 60 * 161 + 80;
  const double luma = 0.299 * reference.pixels[3 * centre] +
                      0.587 * reference.pixels[3 * centre + 1] +
                      0.114 * reference.pixels[3 * centre + 2];
  EXPECT_NEAR(planes->y[centre], luma, 2.0);

  // A grey JPEG (one component, as a mono camera's): neutral chroma planes at half size.
  cv::Mat grey(48, 64, CV_8UC1);
  for (int r = 0; r < grey.rows; ++r) {
    for (int c = 0; c < grey.cols; ++c)
      grey.at<std::uint8_t>(r, c) = static_cast<std::uint8_t>(3 * c);
  }
  // TurboJPEG's own grey encoder (the stream's encoder sends colour).
  std::vector<std::uint8_t> grey_bytes;
  {
    tjhandle compressor = tjInitCompress();
    ASSERT_NE(compressor, nullptr);
    unsigned char* jpeg = nullptr;
    unsigned long jpeg_size = 0;
    ASSERT_EQ(tjCompress2(compressor, grey.data, grey.cols, 0, grey.rows, TJPF_GRAY, &jpeg,
                          &jpeg_size, TJSAMP_GRAY, 90, 0),
              0)
        << tjGetErrorStr2(compressor);
    grey_bytes.assign(jpeg, jpeg + jpeg_size);
    tjFree(jpeg);
    tjDestroy(compressor);
  }
  auto grey_planes = decoder.decode_planes(
      std::string_view(reinterpret_cast<const char*>(grey_bytes.data()), grey_bytes.size()));
  ASSERT_TRUE(grey_planes) << grey_planes.error().message;
  EXPECT_EQ(grey_planes->chroma_width, 32);
  EXPECT_EQ(grey_planes->chroma_height, 24);
  for (const std::uint8_t c : grey_planes->cr) ASSERT_EQ(c, 128);
  EXPECT_NEAR(grey_planes->y[10 * 64 + 20], 60, 3);

  auto garbage = decoder.decode_planes("this is not a JPEG at all, just text");
  ASSERT_FALSE(garbage);
  EXPECT_THAT(garbage.error().message, HasSubstr("JPEG decode: not a readable JPEG header"));
  auto cut = decoder.decode_planes(jpeg->substr(0, jpeg->size() / 2));
  ASSERT_FALSE(cut);
  EXPECT_THAT(cut.error().message, HasSubstr("JPEG decode: corrupt 161x121 image"));
  auto big = decoder.decode_planes(*jpeg, 100 * 100);
  ASSERT_FALSE(big);
  EXPECT_THAT(big.error().message, HasSubstr("beyond the limit of 10000 pixels"));
  // Both eyes at once, as one decoder would.
  StereoJpegDecoder pair_decoder;
  auto pair = pair_decoder.decode_planes(*jpeg, *jpeg);
  ASSERT_TRUE(pair) << pair.error().message;
  EXPECT_TRUE(pair->left.empty());
  EXPECT_EQ(pair->left_planes.y, planes->y);
  EXPECT_EQ(pair->right_planes.cr, planes->cr);
  auto bad_right = pair_decoder.decode_planes(*jpeg, "");
  ASSERT_FALSE(bad_right);
  EXPECT_THAT(bad_right.error().message, HasSubstr("right eye: JPEG decode: no data"));
}

}  // namespace
}  // namespace telear::net
