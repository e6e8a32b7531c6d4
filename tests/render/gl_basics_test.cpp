// The GL foundation on a headless EGL context: offscreen target and read-back orientation,
// the z-buffer, the video background, PNG files, shader errors.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <numbers>

#include "gl_test_util.hpp"
#include "telear/render/image_io.hpp"
#include "telear/render/offscreen_target.hpp"
#include "telear/render/scene_objects.hpp"
#include "telear/render/video_background.hpp"
#include "telear/render/view_math.hpp"
#include "test_util/temp_dir.hpp"

namespace telear::render {
namespace {

using test::GlTest;
using ::testing::HasSubstr;

using test::kBlack;

class GlBasicsTest : public GlTest {
 protected:
  // 160 x 120, 60 degree vertical field of view; the camera frame is the base frame.
  static constexpr int kW = 160, kH = 120;
  Eigen::Matrix4f projection() const {
    return perspective_cv(std::numbers::pi_v<float> / 3, float(kW) / kH, 0.1f, 20.0f);
  }
  Eigen::Matrix4f identity() const { return Eigen::Matrix4f::Identity(); }
  OffscreenTarget target() {
    auto t = OffscreenTarget::create(kW, kH);
    EXPECT_TRUE(t) << t.error().message;
    return t ? std::move(t.value()) : OffscreenTarget();
  }
  // Unlit, opaque: flat colours that the tests can compare exactly.
  DrawOptions flat() const {
    DrawOptions o;
    o.lighting.ambient = Eigen::Vector3f::Ones();
    o.lighting.diffuse = Eigen::Vector3f::Zero();
    return o;
  }
};

TEST_F(GlBasicsTest, TheContextIsOpenGl33CoreOrLater) {
  EXPECT_FALSE(context()->description().empty());
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  EXPECT_GE(major * 10 + minor, 33) << GlContext::gl_version();
  GLint profile = 0;
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
}

TEST_F(GlBasicsTest, AnInvalidTargetSizeIsAnError) {
  auto t = OffscreenTarget::create(0, 10);
  ASSERT_FALSE(t);
  EXPECT_THAT(t.error().message, HasSubstr("offscreen target 0x10: size must be in [1, "));
}

TEST_F(GlBasicsTest, ReadBackIsInImageOrderWithTheTopRowFirst) {
  // A red cube above the optical axis (y_cam < 0) and a green one below it.
  auto scene = create_scene_renderer(
      {make_cube(0.4f, {0, -0.6f, 3}, {1, 0, 0}), make_cube(0.4f, {0, 0.6f, 3}, {0, 1, 0})});
  ASSERT_TRUE(scene) << scene.error().message;
  OffscreenTarget t = target();
  t.clear();
  scene->draw(projection(), identity(), flat());
  const core::Image img = t.read_rgb();
  ASSERT_EQ(img.width, kW);
  ASSERT_EQ(img.height, kH);
  ASSERT_EQ(gl_errors(), "");
  long red_top = 0, red_bottom = 0, green_top = 0, green_bottom = 0;
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      const bool red = img.at(x, y, 0) > 200 && img.at(x, y, 1) < 50;
      const bool green = img.at(x, y, 1) > 200 && img.at(x, y, 0) < 50;
      (y < kH / 2 ? red_top : red_bottom) += red;
      (y < kH / 2 ? green_top : green_bottom) += green;
    }
  }
  EXPECT_GT(red_top, 100);
  EXPECT_EQ(red_bottom, 0);
  EXPECT_GT(green_bottom, 100);
  EXPECT_EQ(green_top, 0);
  // RGBA read-back agrees with RGB.
  const core::Image rgba = t.read_rgba();
  EXPECT_EQ(rgba.at(kW / 2, kH / 4, 0), img.at(kW / 2, kH / 4, 0));
  EXPECT_EQ(rgba.at(kW / 2, kH / 4, 3), 255);
}

TEST_F(GlBasicsTest, FramesAndReadBackKeepEveryPixelAtOddWidths) {
  // 37 x 23: the 4-pixel packing loops have a tail; every pixel goes up and comes back.
  constexpr int w = 37, h = 23;
  core::Image frame(w, h, 3);
  for (std::size_t i = 0; i < frame.pixels.size(); ++i) {
    frame.pixels[i] = static_cast<std::uint8_t>((i * 37) % 251);
  }
  auto bg = VideoBackground::create(w, h);
  auto t = OffscreenTarget::create(w, h);
  ASSERT_TRUE(bg && t);
  for (ChannelOrder order : {ChannelOrder::kRgb, ChannelOrder::kBgr}) {
    t->clear();
    bg->upload(frame.pixels.data(), order);
    bg->draw();
    const core::Image rgb = t->read_rgb();
    const core::Image rgba = t->read_rgba();
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        for (int c = 0; c < 3; ++c) {
          const int source = order == ChannelOrder::kRgb ? c : 2 - c;
          ASSERT_EQ(rgb.at(x, y, c), frame.at(x, y, source)) << x << "," << y << "," << c;
          ASSERT_EQ(rgba.at(x, y, c), frame.at(x, y, source)) << x << "," << y << "," << c;
        }
        ASSERT_EQ(rgba.at(x, y, 3), 255);
      }
    }
  }
}

TEST_F(GlBasicsTest, ANearObjectHidesAFarOneWhateverTheDrawOrder) {
  const SceneObject near_cube = make_cube(0.5f, {0, 0, 2}, {1, 0, 0});
  const SceneObject far_cube = make_cube(2.5f, {0, 0, 6}, {0, 0, 1});
  for (bool near_first : {true, false}) {
    // Each cube in its own renderer so that the draw order is the test's choice.
    auto a = create_scene_renderer({near_first ? near_cube : far_cube});
    auto b = create_scene_renderer({near_first ? far_cube : near_cube});
    ASSERT_TRUE(a && b);
    OffscreenTarget t = target();
    t.clear();
    a->draw(projection(), identity(), flat());
    b->draw(projection(), identity(), flat());
    const core::Image img = t.read_rgb();
    SCOPED_TRACE(near_first ? "near drawn first" : "far drawn first");
    // Centre: the near red cube; a corner of the far cube's silhouette: blue.
    EXPECT_EQ(img.at(kW / 2, kH / 2, 0), 255);
    EXPECT_EQ(img.at(kW / 2, kH / 2, 2), 0);
    const test::Box box = test::covered_box(img, kBlack);
    ASSERT_FALSE(box.empty());
    EXPECT_EQ(img.at(box.min_x + 2, box.min_y + 2, 2), 255);
    EXPECT_EQ(img.at(box.min_x + 2, box.min_y + 2, 0), 0);
  }
}

// Multisampling: an edge pixel holds the share of its area the surface covers, as a camera's
// pixel integrates light, where point sampling gives a staircase of whole pixels (which moves
// a detected marker corner by up to half a pixel: issue 26, docs/demo.md).
TEST_F(GlBasicsTest, AMultisampledTargetShadesEdgePixelsByTheirCoverage) {
  // A white cube turned 10 deg about the optical axis: oblique edges across the pixel grid.
  const Eigen::Matrix4f turned =
      (Eigen::Affine3f(Eigen::AngleAxisf(0.1745f, Eigen::Vector3f::UnitZ()))).matrix();
  auto scene = create_scene_renderer({make_cube(0.8f, {0.01f, 0.02f, 3}, {1, 1, 1})});
  ASSERT_TRUE(scene) << scene.error().message;
  long partial[2] = {0, 0}, white_area[2] = {0, 0};
  const int samples[2] = {1, 4};
  for (int i = 0; i < 2; ++i) {
    auto t = OffscreenTarget::create(kW, kH, samples[i]);
    ASSERT_TRUE(t) << t.error().message;
    EXPECT_EQ(t->samples(), samples[i]);
    t->clear();
    scene->draw(projection(), turned, flat());
    const core::Image img = t->read_rgb();
    ASSERT_EQ(gl_errors(), "");
    for (int y = 0; y < kH; ++y) {
      for (int x = 0; x < kW; ++x) {
        const int v = img.at(x, y, 0);
        if (v > 10 && v < 245) ++partial[i];
        white_area[i] += v;
      }
    }
  }
  // The cube's outline is ~4 x 28 px long at this distance (0.8 m at 3 m, f = 104 px).
  EXPECT_EQ(partial[0], 0) << "point sampling: every pixel all cube or all background";
  EXPECT_GT(partial[1], 50) << "4 samples: the edge pixels in between";
  // The same area either way, to a fraction of the outline.
  EXPECT_NEAR(static_cast<double>(white_area[1]) / white_area[0], 1.0, 0.02);
}

TEST_F(GlBasicsTest, MoreSamplesThanTheDriverAllowsIsAnError) {
  GLint max_samples = 0;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  auto t = OffscreenTarget::create(16, 16, max_samples + 1);
  ASSERT_FALSE(t);
  EXPECT_THAT(t.error().message,
              HasSubstr("offscreen target 16x16: " + std::to_string(max_samples + 1) +
                        " samples per pixel, this OpenGL driver allows 1 to " +
                        std::to_string(std::max(1, max_samples))));
  EXPECT_FALSE(OffscreenTarget::create(16, 16, 0));
}

TEST_F(GlBasicsTest, VideoBackgroundIsUprightAndSwapsBgr) {
  // Top half red, bottom half blue, in the given byte order.
  constexpr int w = 64, h = 48;
  core::Image frame(w, h, 3);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) frame.at(x, y, y < h / 2 ? 0 : 2) = 255;
  }
  auto bg = VideoBackground::create(w, h);
  ASSERT_TRUE(bg) << bg.error().message;
  OffscreenTarget t = target();
  for (ChannelOrder order : {ChannelOrder::kRgb, ChannelOrder::kBgr}) {
    t.clear();
    bg->upload(frame.pixels.data(), order);
    bg->draw();
    const core::Image img = t.read_rgb();
    const int top_channel = order == ChannelOrder::kRgb ? 0 : 2;
    EXPECT_EQ(img.at(kW / 2, 5, top_channel), 255);
    EXPECT_EQ(img.at(kW / 2, 5, 2 - top_channel), 0);
    EXPECT_EQ(img.at(kW / 2, kH - 5, 2 - top_channel), 255);
  }
  ASSERT_EQ(gl_errors(), "");
}

// Issue 23: a decoded JPEG's Y'CbCr planes go up as they are and the GPU converts them: the
// same image as the CPU's conversion (core::to_rgb), upright, at even and odd sizes (an odd
// size's chroma plane rounds up).
TEST_F(GlBasicsTest, VideoPlanesAreConvertedOnTheGpuAsOnTheCpu) {
  for (const auto& [w, h] : {std::pair{160, 120}, std::pair{161, 121}}) {
    core::YCbCrImage planes;
    planes.width = w;
    planes.height = h;
    planes.chroma_width = (w + 1) / 2;
    planes.chroma_height = (h + 1) / 2;
    planes.y.resize(static_cast<std::size_t>(w) * h);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        planes.y[static_cast<std::size_t>(y) * w + x] = static_cast<std::uint8_t>(40 + x + y / 2);
      }
    }
    planes.cb.resize(static_cast<std::size_t>(planes.chroma_width) * planes.chroma_height);
    planes.cr.resize(planes.cb.size());
    for (int y = 0; y < planes.chroma_height; ++y) {
      for (int x = 0; x < planes.chroma_width; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * planes.chroma_width + x;
        planes.cb[i] = static_cast<std::uint8_t>(y < planes.chroma_height / 2 ? 90 : 170);
        planes.cr[i] = static_cast<std::uint8_t>(100 + x);
      }
    }
    auto bg = VideoBackground::create(w, h);
    ASSERT_TRUE(bg) << bg.error().message;
    auto t = OffscreenTarget::create(w, h);
    ASSERT_TRUE(t) << t.error().message;
    t->clear();
    bg->upload_planes(planes);
    t->bind();
    bg->draw();
    const core::Image gpu = t->read_rgb();
    const core::Image cpu = core::to_rgb(planes);
    ASSERT_EQ(gpu.pixels.size(), cpu.pixels.size());
    int worst = 0;
    for (std::size_t i = 0; i < gpu.pixels.size(); ++i) {
      worst = std::max(worst, std::abs(gpu.pixels[i] - cpu.pixels[i]));
    }
    EXPECT_LE(worst, 2) << w << "x" << h;  // float shader against rounded double arithmetic
    // Upright: Cb 90 on the top half is less blue than 170 on the bottom.
    EXPECT_LT(gpu.at(w / 2, 2, 2) + 40, gpu.at(w / 2, h - 3, 2)) << w << "x" << h;
    ASSERT_EQ(gl_errors(), "");
  }
}

TEST_F(GlBasicsTest, ObjectsDrawnAfterTheBackgroundLandOnTop) {
  core::Image frame(32, 32, 3);
  std::fill(frame.pixels.begin(), frame.pixels.end(), 100);
  auto bg = VideoBackground::create(32, 32);
  auto scene = create_scene_renderer({make_cube(0.5f, {0, 0, 2}, {1, 0, 0})});
  ASSERT_TRUE(bg && scene);
  OffscreenTarget t = target();
  t.clear();
  bg->upload(frame.pixels.data(), ChannelOrder::kRgb);
  bg->draw();
  scene->draw(projection(), identity(), flat());
  const core::Image img = t.read_rgb();
  EXPECT_EQ(img.at(kW / 2, kH / 2, 0), 255);
  EXPECT_EQ(img.at(2, 2, 0), 100);
}

TEST_F(GlBasicsTest, PngRoundTrip) {
  core::Image img(7, 5, 3);
  for (std::size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = static_cast<uint8_t>(i * 7);
  test_files::TempDir tmp("render_png");
  const std::string path = tmp.file("frame.png");
  ASSERT_TRUE(write_png(path, img));
  auto back = read_image(path);
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_EQ(back->pixels, img.pixels);
  std::remove(path.c_str());
  auto missing = read_image("/nonexistent/frame.png");
  ASSERT_FALSE(missing);
  EXPECT_THAT(missing.error().message, HasSubstr("cannot read image '/nonexistent/frame.png'"));
  EXPECT_FALSE(write_png("/nonexistent/dir/out.png", img));
  EXPECT_THAT(write_png(path, core::Image()).error().message, HasSubstr("not a valid"));
}

TEST_F(GlBasicsTest, AShaderErrorCarriesTheDriverLog) {
  auto p = Program::link("#version 330 core\nvoid main() { gl_Position = vec4(oops); }\n",
                         "#version 330 core\nout vec4 c; void main() { c = vec4(1); }\n", "broken");
  ASSERT_FALSE(p);
  EXPECT_THAT(p.error().message, HasSubstr("shader 'broken' (vertex) does not compile"));
  EXPECT_THAT(p.error().message, HasSubstr("oops"));
}

}  // namespace
}  // namespace telear::render
