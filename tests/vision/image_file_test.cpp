#include "telear/vision/image_file.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <turbojpeg.h>

#include <fstream>
#include <opencv2/imgproc.hpp>

#include "test_util/temp_dir.hpp"

namespace telear::vision {
namespace {

using ::testing::HasSubstr;

// A picture whose channels differ everywhere, so a swapped channel order cannot pass.
cv::Mat gradient(int type) {
  cv::Mat image(37, 53, type);
  const int channels = image.channels();
  const double top = image.depth() == CV_16U ? 65535.0 : 255.0;
  for (int r = 0; r < image.rows; ++r) {
    for (int c = 0; c < image.cols; ++c) {
      for (int k = 0; k < channels; ++k) {
        const double v = top * ((r * 7 + c * 3 + k * 50) % 256) / 255.0;
        if (image.depth() == CV_16U) {
          image.ptr<std::uint16_t>(r)[c * channels + k] = static_cast<std::uint16_t>(v);
        } else {
          image.ptr<std::uint8_t>(r)[c * channels + k] = static_cast<std::uint8_t>(v);
        }
      }
    }
  }
  return image;
}

bool same(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0.0;
}

TEST(ImageFile, PngRoundTripsEveryDepthAndChannelCountInOpenCvsOrder) {
  test_files::TempDir dir("image_file");
  for (const int type : {CV_8UC1, CV_8UC3, CV_8UC4, CV_16UC1, CV_16UC3}) {
    const cv::Mat image = gradient(type);
    const std::string path = dir.file("image.png");
    ASSERT_TRUE(write_png_file(path, image)) << type;
    auto read = read_image_file(path, ImageFileMode::kUnchanged);
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_TRUE(same(*read, image)) << "type " << type;
  }
}

TEST(ImageFile, GreyAndColourModesConvertAsOpenCvDoes) {
  test_files::TempDir dir("image_file");
  const cv::Mat bgr = gradient(CV_8UC3);
  ASSERT_TRUE(write_png_file(dir.file("bgr.png"), bgr));
  auto grey = read_image_file(dir.file("bgr.png"), ImageFileMode::kGrey);
  ASSERT_TRUE(grey) << grey.error().message;
  cv::Mat expected;
  cv::cvtColor(bgr, expected, cv::COLOR_BGR2GRAY);
  EXPECT_TRUE(same(*grey, expected));

  // A grey file read as colour: three equal channels; 16 bits read as 8 by the top byte.
  const cv::Mat deep = gradient(CV_16UC1);
  ASSERT_TRUE(write_png_file(dir.file("deep.png"), deep));
  auto colour = read_image_file(dir.file("deep.png"), ImageFileMode::kColour);
  ASSERT_TRUE(colour) << colour.error().message;
  ASSERT_EQ(colour->type(), CV_8UC3);
  cv::Mat eight;
  deep.convertTo(eight, CV_8U, 1.0 / 257.0);
  cv::Mat planes[3];
  cv::split(*colour, planes);
  for (const cv::Mat& plane : planes) EXPECT_TRUE(same(plane, eight));
}

TEST(ImageFile, ReadsJpegFilesInOpenCvsChannelOrder) {
  test_files::TempDir dir("image_file");
  const cv::Mat bgr = gradient(CV_8UC3);
  tjhandle compressor = tjInitCompress();
  unsigned char* jpeg = nullptr;
  unsigned long size = 0;
  ASSERT_EQ(tjCompress2(compressor, bgr.data, bgr.cols, 0, bgr.rows, TJPF_BGR, &jpeg, &size,
                        TJSAMP_444, 95, 0),
            0);
  std::ofstream(dir.file("photo.jpg"), std::ios::binary)
      .write(reinterpret_cast<const char*>(jpeg), static_cast<std::streamsize>(size));
  tjFree(jpeg);
  tjDestroy(compressor);
  auto read = read_image_file(dir.file("photo.jpg"), ImageFileMode::kColour);
  ASSERT_TRUE(read) << read.error().message;
  ASSERT_EQ(read->type(), CV_8UC3);
  // Lossy, but the channels are in place: each within a few levels of the original.
  cv::Mat difference;
  cv::absdiff(*read, bgr, difference);
  EXPECT_LT(cv::mean(difference)[0], 4.0);
  EXPECT_LT(cv::mean(difference)[2], 4.0);
}

TEST(ImageFile, ErrorsNameTheFileAndWhy) {
  test_files::TempDir dir("image_file");
  auto missing = read_image_file(dir.file("nothing.png"), ImageFileMode::kGrey);
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().message,
            "cannot read image '" + dir.file("nothing.png") + "': cannot open the file");

  std::ofstream(dir.file("text.png")) << "not a picture";
  auto text = read_image_file(dir.file("text.png"), ImageFileMode::kUnchanged);
  ASSERT_FALSE(text);
  EXPECT_THAT(text.error().message,
              HasSubstr("cannot read image '" + dir.file("text.png") + "': "));

  // A truncated PNG: the header promises rows the file does not hold.
  ASSERT_TRUE(write_png_file(dir.file("whole.png"), gradient(CV_8UC3)));
  std::ifstream whole(dir.file("whole.png"), std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(whole)), std::istreambuf_iterator<char>());
  std::ofstream(dir.file("cut.png"), std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  EXPECT_FALSE(read_image_file(dir.file("cut.png"), ImageFileMode::kUnchanged));

  Status empty = write_png_file(dir.file("empty.png"), cv::Mat());
  ASSERT_FALSE(empty);
  EXPECT_EQ(empty.error().message,
            "cannot write PNG file '" + dir.file("empty.png") + "': empty image");
  Status floats = write_png_file(dir.file("float.png"), cv::Mat(4, 4, CV_32FC1, cv::Scalar(0.5)));
  ASSERT_FALSE(floats);
  EXPECT_EQ(floats.error().message, "cannot write PNG file '" + dir.file("float.png") +
                                        "': a PNG holds 8- or 16-bit images of 1, 3 or 4 channels");
  // Inside a file, not a folder.
  const std::string inside_a_file = dir.write("plain", "x") + "/image.png";
  Status nowhere = write_png_file(inside_a_file, gradient(CV_8UC1));
  ASSERT_FALSE(nowhere);
  EXPECT_EQ(nowhere.error().message,
            "cannot write PNG file '" + inside_a_file + "': cannot create the file");
}

}  // namespace
}  // namespace telear::vision
