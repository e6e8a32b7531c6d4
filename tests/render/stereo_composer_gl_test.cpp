// Stereo composition on a headless EGL context: each layout puts each eye where it belongs.
// The eyes are two distinct pictures: the left eye dark red with a white square in its
// top-left quarter, the right eye dark blue with a white square in its bottom-right quarter,
// so a swapped, flipped or mirrored eye is caught.

#include "telear/render/stereo_composer.hpp"

#include <gtest/gtest.h>

#include "gl_test_util.hpp"

namespace telear::render {
namespace {

using test::GlTest;

constexpr int kEyeW = 64, kEyeH = 48;

// Fills the target's top-left (or bottom-right) 16x12 square white over `colour`.
void paint_eye(const OffscreenTarget& eye, const Eigen::Vector3f& colour, bool top_left) {
  eye.clear(colour.x(), colour.y(), colour.z(), 1.0f);
  glEnable(GL_SCISSOR_TEST);
  // GL rows go up: the image's top rows are the framebuffer's last ones.
  if (top_left) {
    glScissor(4, kEyeH - 4 - 12, 16, 12);
  } else {
    glScissor(kEyeW - 4 - 16, 4, 16, 12);
  }
  glClearColor(1, 1, 1, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  glDisable(GL_SCISSOR_TEST);
}

Eigen::Vector3i rgb(const core::Image& image, int x, int y) {
  return {image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2)};
}

class StereoComposerTest : public GlTest {
 protected:
  void SetUp() override {
    GlTest::SetUp();
    if (HasFatalFailure()) return;
    auto l = OffscreenTarget::create(kEyeW, kEyeH);
    auto r = OffscreenTarget::create(kEyeW, kEyeH);
    auto c = StereoComposer::create();
    ASSERT_TRUE(l) << l.error().message;
    ASSERT_TRUE(r) << r.error().message;
    ASSERT_TRUE(c) << c.error().message;
    left = std::move(l.value());
    right = std::move(r.value());
    composer = std::move(c.value());
    paint_eye(left, {0.5f, 0.0f, 0.0f}, true);
    paint_eye(right, {0.0f, 0.0f, 0.5f}, false);
  }

  core::Image compose(StereoLayout layout) {
    const ComposedSize size = composed_size(layout, kEyeW, kEyeH);
    auto out = OffscreenTarget::create(size.width, size.height);
    EXPECT_TRUE(out);
    out->clear(0, 1, 0, 1);  // green: any pixel left uncovered shows
    composer.compose(layout, left.colour_texture(), right.colour_texture(), *out);
    return out->read_rgb();
  }

  // The eye pictures as read back, for comparison with the composed regions.
  void expect_region_is_eye(const core::Image& out, int x0, int y0, const core::Image& eye,
                            const std::string& what) {
    int mismatches = 0;
    for (int y = 0; y < kEyeH; ++y) {
      for (int x = 0; x < kEyeW; ++x) {
        if (rgb(out, x0 + x, y0 + y) != rgb(eye, x, y)) ++mismatches;
      }
    }
    EXPECT_EQ(mismatches, 0) << what;
  }

  OffscreenTarget left, right;
  StereoComposer composer;
};

TEST_F(StereoComposerTest, EyesReadBackAsPainted) {
  const core::Image l = left.read_rgb();
  EXPECT_EQ(rgb(l, 5, 5), Eigen::Vector3i(255, 255, 255));  // top-left square
  EXPECT_EQ(rgb(l, kEyeW - 6, kEyeH - 6), Eigen::Vector3i(128, 0, 0));
  const core::Image r = right.read_rgb();
  EXPECT_EQ(rgb(r, kEyeW - 6, kEyeH - 6), Eigen::Vector3i(255, 255, 255));  // bottom-right square
  EXPECT_EQ(rgb(r, 5, 5), Eigen::Vector3i(0, 0, 128));
}

TEST_F(StereoComposerTest, SideBySidePutsTheLeftEyeOnTheLeft) {
  const core::Image out = compose(StereoLayout::kSideBySide);
  ASSERT_EQ(out.width, 2 * kEyeW);
  ASSERT_EQ(out.height, kEyeH);
  expect_region_is_eye(out, 0, 0, left.read_rgb(), "left half = left eye");
  expect_region_is_eye(out, kEyeW, 0, right.read_rgb(), "right half = right eye");
}

TEST_F(StereoComposerTest, TopBottomPutsTheLeftEyeOnTop) {
  const core::Image out = compose(StereoLayout::kTopBottom);
  ASSERT_EQ(out.width, kEyeW);
  ASSERT_EQ(out.height, 2 * kEyeH);
  expect_region_is_eye(out, 0, 0, left.read_rgb(), "top half = left eye");
  expect_region_is_eye(out, 0, kEyeH, right.read_rgb(), "bottom half = right eye");
}

TEST_F(StereoComposerTest, AnaglyphIsLeftInRedAndRightInCyan) {
  const core::Image out = compose(StereoLayout::kAnaglyph);
  ASSERT_EQ(out.width, kEyeW);
  // Left eye's white square: red = 255; right eye there is dark blue: green 0, blue 128.
  EXPECT_EQ(rgb(out, 8, 8), Eigen::Vector3i(255, 0, 128));
  // Right eye's white square: cyan 255, 255; left eye there is dark red: luminance 0.299*128.
  EXPECT_NEAR(rgb(out, kEyeW - 8, kEyeH - 8).x(), 38, 1);
  EXPECT_EQ(rgb(out, kEyeW - 8, kEyeH - 8).tail<2>(), Eigen::Vector2i(255, 255));
  // Elsewhere: red from the left eye's luminance, blue from the right eye.
  EXPECT_NEAR(rgb(out, kEyeW / 2, kEyeH / 2).x(), 38, 1);
  EXPECT_EQ(rgb(out, kEyeW / 2, kEyeH / 2).z(), 128);
}

TEST_F(StereoComposerTest, LayoutNamesAndSizes) {
  EXPECT_EQ(*parse_stereo_layout("sbs"), StereoLayout::kSideBySide);
  EXPECT_EQ(*parse_stereo_layout("tb"), StereoLayout::kTopBottom);
  EXPECT_EQ(*parse_stereo_layout("anaglyph"), StereoLayout::kAnaglyph);
  EXPECT_EQ(*parse_stereo_layout("separate"), StereoLayout::kSeparate);
  EXPECT_EQ(parse_stereo_layout("over-under").error().message,
            "unknown stereo layout 'over-under' (use sbs, tb, anaglyph or separate)");
  EXPECT_EQ(composed_size(StereoLayout::kSeparate, 640, 480).width, 640);
  EXPECT_EQ(composed_size(StereoLayout::kTopBottom, 640, 480).height, 960);
}

TEST_F(StereoComposerTest, PageFlippingNeedsAStereoVisualAndFallsBackCleanly) {
  // A headless context has no quad-buffer visual: an error, nothing drawn.
  const Status status = composer.present_page_flipped(*context(), left.colour_texture(),
                                                      right.colour_texture(), kEyeW, kEyeH);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.error().message.find("has no quad-buffer stereo visual"), std::string::npos)
      << status.error().message;
  const WindowStereo fallback = choose_window_stereo(false);
  EXPECT_FALSE(fallback.page_flipped);
  EXPECT_EQ(fallback.fallback, StereoLayout::kSideBySide);
  EXPECT_EQ(fallback.message,
            "quad-buffer stereo is not available (the GL driver offers no stereo visual); "
            "showing the two eyes side by side instead");
  EXPECT_TRUE(choose_window_stereo(true).page_flipped);
  EXPECT_EQ(gl_errors(), "");
}

}  // namespace
}  // namespace telear::render
