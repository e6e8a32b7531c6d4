// Issue 23, item 5: the console's video decoded to Y'CbCr planes and converted on the GPU
// (`--video-planes on`; auto picks it on a hardware GPU, RGB on llvmpipe): the session's frames
// carry planes and no RGB, and the AR view shows the same video as the CPU's conversion.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <sstream>

#include "scripted_console.hpp"
#include "telear/console/console_app.hpp"
#include "telear/render/gl_context.hpp"
#include "test_util/temp_dir.hpp"

namespace telear::console {
namespace {

using ::testing::HasSubstr;

TEST(ConsoleVideoPlanes, TheViewDrawsTheDecodedPlanesAsTheCpuWouldConvertThem) {
  test_files::TempDir tmp("planes");
  const std::string script = (tmp.path() / "video.txt").string();
  // AR after 5 fresh frames and 0.5 s; the test ends at the first AR frame (a loaded machine
  // may take seconds).
  std::ofstream(script) << "wait-until video 30\nwait 30\n";
  ConsoleOptions options = telear::test::scripted_headless_console(script, 800, 500);
  options.frames = 0;
  options.video_planes = "on";
  std::ostringstream log;
  auto created = ConsoleApp::create(options, log);
  ASSERT_TRUE(created) << created.error().message;
  ConsoleApp& app = **created;
  EXPECT_THAT(log.str(), HasSubstr("video decoded to Y'CbCr planes, converted on the GPU"));
  const auto start = std::chrono::steady_clock::now();
  int compared = 0;
  while (app.frame()) {
    ASSERT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 60.0)
        << log.str();
    const session::SessionView& v = app.session().view();
    if (!v.frame || v.display.mode != session::DisplayMode::kAR || compared > 0) continue;
    ASSERT_TRUE(v.frame->left.empty());  // no CPU colour conversion
    ASSERT_EQ(v.frame->left_planes.width, 320);
    ASSERT_EQ(v.frame->left_planes.chroma_width, 160);
    // The left eye's top-left corner (inside the 4 px status border): the scene's background,
    // as the CPU converts the same planes.
    const core::Image view = app.read_view_image();
    const core::Image cpu = core::to_rgb(v.frame->left_planes);
    int worst = 0;
    for (int y = 10; y < 40; ++y) {
      for (int x = 10; x < 120; ++x) {
        for (int c = 0; c < 3; ++c)
          worst = std::max(worst, std::abs(view.at(x, y, c) - cpu.at(x, y, c)));
      }
    }
    EXPECT_LE(worst, 2);
    ++compared;
    break;
  }
  EXPECT_EQ(compared, 1) << log.str();
}

TEST(ConsoleVideoPlanes, ABadSettingIsRefusedAndAutoIsRgbOnASoftwareRenderer) {
  test_files::TempDir tmp("planes-bad");
  const std::string script = (tmp.path() / "none.txt").string();
  std::ofstream(script) << "wait 0.1\n";
  ConsoleOptions options = telear::test::scripted_headless_console(script, 800, 500);
  options.frames = 1;
  options.video_planes = "sometimes";
  std::ostringstream log;
  auto bad = ConsoleApp::create(options, log);
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().message, "video_planes 'sometimes': auto, on or off");
  options.video_planes = "auto";
  auto app = ConsoleApp::create(options, log);
  ASSERT_TRUE(app) << app.error().message;
  // On llvmpipe (CI) the CPU's SIMD conversion is the cheaper: RGB; on a hardware GPU, planes.
  const std::string renderer = render::GlContext::gl_renderer();
  EXPECT_THAT(log.str(), HasSubstr(render::is_software_renderer(renderer)
                                       ? "video decoded to RGB (renderer " + renderer + ")"
                                       : "video decoded to Y'CbCr planes, converted on the GPU"));
}

}  // namespace
}  // namespace telear::console
