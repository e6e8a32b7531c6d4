// The stereo sources that read through OpenCV's videoio (video files, V4L2 cameras): their own
// executable, like their own library (telear::vision_videoio), so the other test programs do not
// load videoio's shared libraries at each start.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "telear/vision/camera_source.hpp"
#include "telear/vision/video_file_source.hpp"

namespace telear::vision {
namespace {

using ::testing::StartsWith;

const char* const kVtest = "/usr/share/doc/opencv-doc/examples/data/vtest.avi";

TEST(VideoFileSource, DecodesOpenCvsSampleVideo) {
  if (!std::filesystem::exists(kVtest)) GTEST_SKIP() << kVtest << " missing (apt opencv-doc)";
  auto source = VideoFileSource::open({kVtest, kVtest, 1000.0, 0, 0});
  ASSERT_TRUE(source) << source.error().message;
  EXPECT_EQ((*source)->name(), "files");
  EXPECT_EQ((*source)->width(), 768);
  EXPECT_EQ((*source)->height(), 576);
  auto first = (*source)->capture();
  auto second = (*source)->capture();
  ASSERT_TRUE(first && second) << (first ? second.error().message : first.error().message);
  EXPECT_EQ(first->frame_number, 1u);
  EXPECT_EQ(second->frame_number, 2u);
  EXPECT_EQ(first->left.width, 768);
  EXPECT_EQ(first->left.channels, 3);
  // The same file for both eyes: the same picture.
  EXPECT_EQ(first->left.pixels, first->right.pixels);
  // A real video: frames differ (people walk).
  EXPECT_NE(first->left.pixels, second->left.pixels);
}

TEST(VideoFileSource, ScalesToAGivenSize) {
  if (!std::filesystem::exists(kVtest)) GTEST_SKIP() << kVtest << " missing";
  auto source = VideoFileSource::open({kVtest, kVtest, 1000.0, 320, 240});
  ASSERT_TRUE(source);
  auto pair = (*source)->capture();
  ASSERT_TRUE(pair);
  EXPECT_EQ(pair->left.width, 320);
  EXPECT_EQ(pair->right.height, 240);
}

TEST(VideoFileSource, MissingFileSaysSo) {
  auto source = VideoFileSource::open({"/nonexistent/left.avi", kVtest, 0, 0, 0});
  ASSERT_FALSE(source);
  EXPECT_EQ(source.error().message, "video file '/nonexistent/left.avi': no such file");
}

TEST(CameraSource, MissingCameraHasAClearMessage) {
  CameraSourceOptions options;
  options.left_index = 63;  // /dev/video63: not a camera on any test machine
  options.right_index = 62;
  auto source = CameraSource::open(options);
  ASSERT_FALSE(source);
  EXPECT_THAT(source.error().message, StartsWith("no camera at /dev/video63: "));
}

}  // namespace
}  // namespace telear::vision
