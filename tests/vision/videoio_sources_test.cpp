// What reads and writes through OpenCV's videoio (video files, V4L2 cameras, MP4), through the
// plugin libtelear_videoio.so that vision loads at its first use (telear/vision/videoio.hpp):
// their own executable, so that only this test program loads videoio's shared libraries.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <link.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "telear/vision/videoio.hpp"
#include "test_util/temp_dir.hpp"

namespace telear::vision {
namespace {

using ::testing::EndsWith;
using ::testing::HasSubstr;
using ::testing::StartsWith;

const char* const kVtest = "/usr/share/doc/opencv-doc/examples/data/vtest.avi";

// Whether a shared library whose name contains `part` is loaded in this process.
bool loaded(const std::string& part) {
  struct Search {
    std::string part;
    bool found = false;
  } search{part};
  dl_iterate_phdr(
      [](dl_phdr_info* info, std::size_t, void* data) {
        auto* s = static_cast<Search*>(data);
        if (info->dlpi_name && std::string(info->dlpi_name).find(s->part) != std::string::npos) {
          s->found = true;
        }
        return 0;
      },
      &search);
  return search.found;
}

// The plugin is loaded once per process, so each of these runs in a process of its own: gtest's
// threadsafe death-test style runs this program again for the one statement, whatever ran
// before in this process. The child prints what it found, and the parent matches it.
class VideoioPlugin : public ::testing::Test {
 protected:
  void SetUp() override { GTEST_FLAG_SET(death_test_style, "threadsafe"); }
};

std::string message(const Result<std::string>& r) {
  return r ? *r : r.error().message;
}

TEST_F(VideoioPlugin, VideoioIsLoadedOnlyWhenAVideoIsOpened) {
  EXPECT_EXIT(
      {
        const bool before = loaded("libopencv_videoio");
        const std::string path = message(videoio_plugin_path());
        std::fprintf(stderr, "before %d; %s; after %d\n", before, path.c_str(),
                     loaded("libopencv_videoio"));
        std::_Exit(0);
      },
      ::testing::ExitedWithCode(0), "before 0; /[^;]*/libtelear_videoio\\.so; after 1");
}

TEST_F(VideoioPlugin, APluginThatDoesNotLoadIsNamedWithTheReason) {
  EXPECT_EXIT(
      {
        setenv("TELEAR_VIDEOIO_PLUGIN", "/nonexistent/libtelear_videoio.so", 1);
        auto source = open_video_file_pair({kVtest, kVtest, 0, 0, 0});
        auto writer = open_mp4_writer({"/tmp/never.mp4", 64, 48, 10.0});
        // Every later call gives the same answer, without trying again.
        const bool same = !source && !writer && writer.error().message == source.error().message;
        std::fprintf(stderr, "%s; %s\n", source ? "opened" : source.error().message.c_str(),
                     same ? "the same later" : "another later");
        std::_Exit(0);
      },
      ::testing::ExitedWithCode(0),
      "the videoio plugin TELEAR_VIDEOIO_PLUGIN='/nonexistent/libtelear_videoio\\.so' does not "
      "load: /nonexistent/libtelear_videoio\\.so: [^;]*; the same later");
}

TEST_F(VideoioPlugin, ALibraryThatIsNotThePluginIsRefused) {
  EXPECT_EXIT(
      {
        setenv("TELEAR_VIDEOIO_PLUGIN", "libm.so.6", 1);
        std::fprintf(stderr, "%s\n", message(videoio_plugin_path()).c_str());
        std::_Exit(0);
      },
      ::testing::ExitedWithCode(0), "no telear_videoio_plugin symbol: not telear's videoio plugin");
}

TEST(VideoFileSource, DecodesOpenCvsSampleVideo) {
  if (!std::filesystem::exists(kVtest)) GTEST_SKIP() << kVtest << " missing (apt opencv-doc)";
  auto source = open_video_file_pair({kVtest, kVtest, 1000.0, 0, 0});
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
  auto source = open_video_file_pair({kVtest, kVtest, 1000.0, 320, 240});
  ASSERT_TRUE(source) << source.error().message;
  auto pair = (*source)->capture();
  ASSERT_TRUE(pair);
  EXPECT_EQ(pair->left.width, 320);
  EXPECT_EQ(pair->right.height, 240);
}

TEST(VideoFileSource, MissingFileSaysSo) {
  auto source = open_video_file_pair({"/nonexistent/left.avi", kVtest, 0, 0, 0});
  ASSERT_FALSE(source);
  EXPECT_EQ(source.error().message, "video file '/nonexistent/left.avi': no such file");
}

TEST(CameraSource, MissingCameraHasAClearMessage) {
  CameraSourceOptions options;
  options.left_index = 63;  // /dev/video63: not a camera on any test machine
  options.right_index = 62;
  auto source = open_camera_pair(options);
  ASSERT_FALSE(source);
  EXPECT_THAT(source.error().message, StartsWith("no camera at /dev/video63: "));
}

// The demo's MP4: frames written are read back, at their size, in order.
TEST(Mp4Writer, WritesFramesThatReadBack) {
  test_files::TempDir tmp("mp4");
  const std::string path = tmp.file("out.mp4");
  auto writer = open_mp4_writer({path, 64, 48, 10.0});
  ASSERT_TRUE(writer) << writer.error().message;
  EXPECT_THAT((*writer)->codec(), ::testing::AnyOf("avc1", "mp4v"));
  EXPECT_EQ((*writer)->warning().empty(), (*writer)->codec() == "avc1");
  core::Image frame = core::Image(64, 48, 3);
  for (int i = 0; i < 5; ++i) {
    std::fill(frame.pixels.begin(), frame.pixels.end(), static_cast<std::uint8_t>(40 * i));
    ASSERT_TRUE((*writer)->write(frame).ok());
  }
  // A frame of another size is refused, and named.
  const Status wrong = (*writer)->write(core::Image(32, 24, 3));
  ASSERT_FALSE(wrong.ok());
  EXPECT_EQ(wrong.error().message,
            "the video " + path + " takes 64x48 RGB frames, not 32x24 with 3 channels");
  (*writer)->close();
  EXPECT_FALSE((*writer)->write(frame).ok());

  auto source = open_video_file_pair({path, path, 1000.0, 0, 0});
  ASSERT_TRUE(source) << source.error().message;
  EXPECT_EQ((*source)->width(), 64);
  auto first = (*source)->capture();
  auto second = (*source)->capture();
  ASSERT_TRUE(first && second);
  // Grey 0 then 40, through a lossy codec.
  EXPECT_NEAR(first->left.pixels[64 * 24 * 3 + 96], 0, 6);
  EXPECT_NEAR(second->left.pixels[64 * 24 * 3 + 96], 40, 6);
}

TEST(Mp4Writer, BadSizeOrRateIsRefused) {
  auto writer = open_mp4_writer({"/tmp/x.mp4", 0, 48, 10.0});
  ASSERT_FALSE(writer);
  EXPECT_EQ(writer.error().message,
            "the video /tmp/x.mp4: size 0x48 and rate 10 fps must be positive");
}

}  // namespace
}  // namespace telear::vision
