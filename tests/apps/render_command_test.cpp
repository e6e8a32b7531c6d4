// End-to-end tests of `telear render`: the binary, headless (EGL), writes PNGs of the right
// size and content; every bad input is one line on stderr and a non-zero exit.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "cli_runner.hpp"
#include "telear/render/image_io.hpp"
#include "test_util/temp_dir.hpp"
#include "test_util/test_util.hpp"

namespace telear {
namespace {

using test::run_telear;
using ::testing::HasSubstr;

// `name` in this process's own scratch folder (removed at exit).
std::string temp(const std::string& name) {
  static const test_files::TempDir dir("render_command");
  return dir.file(name);
}

std::string rig() {
  return test::data_path("cameras/puma560_stereo.yaml");
}

// Pixels that differ from the top-left pixel (the background) in a region.
long covered(const core::Image& image, int x0, int x1) {
  long n = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = x0; x < x1; ++x) {
      for (int c = 0; c < 3; ++c) {
        if (std::abs(int(image.at(x, y, c)) - int(image.at(0, 0, c))) > 10) {
          ++n;
          break;
        }
      }
    }
  }
  return n;
}

// Exactly one line on stderr, containing `text`, and exit code 2.
void expect_one_line_error(const test::CommandResult& r, const std::string& text) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr(text));
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind("telear render: ", 0), 0u) << r.err;
}

TEST(CliRender, DefaultViewShowsTheWholeArm) {
  const std::string out = temp("default.png");
  const auto r = run_telear("render --q qn -o " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("wrote " + out + " (640x480, raw overlay, default view)"));
  auto image = render::read_image(out);
  ASSERT_TRUE(image) << image.error().message;
  EXPECT_EQ(image->width, 640);
  EXPECT_EQ(image->height, 480);
  EXPECT_GT(covered(*image, 0, 640), 5000);
  // The whole arm is in view: nothing touches the image border.
  EXPECT_EQ(covered(*image, 0, 2) + covered(*image, 638, 640), 0);
  std::remove(out.c_str());
}

TEST(CliRender, StereoRigSideBySideAndSeparate) {
  const std::string out = temp("sbs.png");
  const auto r = run_telear("render --q qn --camera " + rig() + " --stereo sbs -o " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto sbs = render::read_image(out);
  ASSERT_TRUE(sbs);
  EXPECT_EQ(sbs->width, 1280);
  EXPECT_EQ(sbs->height, 480);
  EXPECT_GT(covered(*sbs, 0, 640), 3000);     // the left eye's arm
  EXPECT_GT(covered(*sbs, 640, 1280), 3000);  // the right eye's arm

  const std::string separate = temp("eye.png");
  const auto s = run_telear("render --q qn --camera " + rig() + " --stereo separate -o " +
                            separate + " --wireframe --segments 8");
  ASSERT_EQ(s.exit_code, 0) << s.err;
  for (const char* eye : {"left", "right"}) {
    const std::string path = temp(std::string("eye_") + eye + ".png");
    auto image = render::read_image(path);
    ASSERT_TRUE(image) << image.error().message;
    EXPECT_EQ(image->width, 640);
    std::remove(path.c_str());
  }
  std::remove(out.c_str());
}

TEST(CliRender, ArmOnABackgroundFrameInBothOverlayModes) {
  const std::string background = temp("bg.png");
  core::Image frame(640, 480, 3);
  for (size_t i = 0; i < frame.pixels.size(); ++i) frame.pixels[i] = (i % 3 == 1) ? 200 : 40;
  ASSERT_TRUE(render::write_png(background, frame));
  for (const char* mode : {"", " --undistort"}) {
    const std::string out = temp("on_video.png");
    const auto r = run_telear("render --q qn --camera " + rig() + " --eye left --background " +
                              background + " --alpha 0.6" + mode + " -o " + out);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    auto image = render::read_image(out);
    ASSERT_TRUE(image);
    // The frame is behind the arm: at the top centre (sky above the arm) it is unchanged.
    EXPECT_EQ(image->at(320, 5, 1), 200);
    std::remove(out.c_str());
  }
  std::remove(background.c_str());
}

TEST(CliRender, BadInputIsOneLineAndNonZero) {
  const std::string out = temp("never.png");
  expect_one_line_error(run_telear("render --q 1,2,3 -o " + out), "--q: expected 6 numbers, got 3");
  expect_one_line_error(run_telear("render --q qn --camera /nonexistent.yaml -o " + out),
                        "cannot open camera file '/nonexistent.yaml'");
  const std::string bad_yaml = temp("bad.yaml");
  std::ofstream(bad_yaml) << "image_width: [640\n";
  expect_one_line_error(run_telear("render --q qn --camera " + bad_yaml + " -o " + out),
                        "not valid YAML at line");
  expect_one_line_error(run_telear("render --q qn --background /nonexistent.png -o " + out),
                        "cannot read image '/nonexistent.png'");
  const std::string not_image = temp("not_image.png");
  std::ofstream(not_image) << "this is not a PNG";
  expect_one_line_error(run_telear("render --q qn --background " + not_image + " -o " + out),
                        "cannot read image '" + not_image + "'");
  const std::string small = temp("small.png");
  ASSERT_TRUE(render::write_png(small, core::Image(320, 240, 3)));
  expect_one_line_error(run_telear("render --q qn --camera " + rig() + " --eye left --background " +
                                   small + " -o " + out),
                        "background image is 320x240 but the left camera's image is 640x480");
  expect_one_line_error(run_telear("render --q qn --eye middle -o " + out),
                        "eye must be left, right or both, got 'middle'");
  expect_one_line_error(
      run_telear("render --q qn --camera " + rig() + " --stereo over-under -o " + out),
      "--stereo: unknown stereo layout 'over-under' (use sbs, tb, anaglyph or separate)");
  expect_one_line_error(run_telear("render --q qn --alpha 1.5 -o " + out),
                        "--alpha must be in (0, 1], got 1.5");
  expect_one_line_error(run_telear("render --q qn --segments 2 -o " + out),
                        "--segments must be in [3, 512], got 2");
  expect_one_line_error(run_telear("render --robot nosuchrobot --q qn -o " + out), "nosuchrobot");
  expect_one_line_error(run_telear("render --q qn -o /nonexistent/dir/out.png"),
                        "cannot write PNG file '/nonexistent/dir/out.png'");
  EXPECT_NE(access(out.c_str(), F_OK), 0);  // nothing was written
  for (const std::string& p : {bad_yaml, not_image, small}) std::remove(p.c_str());
}

}  // namespace
}  // namespace telear
