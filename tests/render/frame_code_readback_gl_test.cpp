// The frame code read back from the AR view's eye (telear/render/frame_code_readback.hpp): in raw
// overlay mode with the eye at the video's size the strip's pixels land where the source wrote
// them, lens distortion or not, and the code reads back exactly in both eyes; without video
// (VR), in the undistorted mode of a distorted camera or on an eye too small, it is absent --
// never another value.
#include "telear/render/frame_code_readback.hpp"

#include <gtest/gtest.h>

#include <random>

#include "gl_test_util.hpp"
#include "telear/core/arm_body.hpp"
#include "telear/core/clock.hpp"
#include "telear/render/ar_view.hpp"
#include "test_util/test_util.hpp"

namespace telear::render {
namespace {

class FrameCodeReadbackTest : public test::GlTest {
 protected:
  void SetUp() override {
    test::GlTest::SetUp();
    model = telear::test::puma560();
    auto description = core::body_description_for(*model);
    ASSERT_TRUE(description) << description.error().message;
    body = core::build_arm_body(*description);
  }

  // The two eyes of a 640x480 rig looking at the arm, with the given lens distortion.
  static vision::StereoCameraModel cameras_with(const vision::Distortion& kc, int width = 640,
                                                int height = 480) {
    const Eigen::Vector3d target(0.3, -0.1, 0.4);
    vision::StereoCameraModel cameras;
    cameras.left = vision::look_at_camera(width, height, 0.9, {2.0, -0.5, 1.0}, target, {0, 0, 1});
    cameras.right =
        vision::look_at_camera(width, height, 0.9, {2.0, -0.44, 1.0}, target, {0, 0, 1});
    cameras.left.kc = kc;
    cameras.right.kc = kc;
    return cameras;
  }

  // A noisy video frame stamped with `code`.
  static core::Image stamped(int width, int height, const vision::FrameCode& code) {
    core::Image image(width, height, 3);
    std::mt19937 rng(static_cast<unsigned>(code.frame));
    for (auto& p : image.pixels) p = static_cast<std::uint8_t>(64 + rng() % 128);
    vision::write_frame_code(image, code);
    return image;
  }

  core::RobotModelPtr model;
  core::ArmBody body;
};

const vision::FrameCode kLeft{41, 1'234'567'890'123};
const vision::FrameCode kRight{41, 1'234'567'890'456};

TEST_F(FrameCodeReadbackTest, RawModeAtTheVideosSizeReadsBothEyesExactly) {
  for (const vision::Distortion& kc :
       {vision::Distortion{}, vision::Distortion::plumb_bob(-0.3, 0.1, 0.001, -0.002, 0)}) {
    auto view =
        ArView::create(*model, body, cameras_with(kc), {},
                       {.layout = StereoLayout::kSideBySide, .overlay_mode = OverlayMode::kRaw});
    ASSERT_TRUE(view) << view.error().message;
    const core::Image left = stamped(640, 480, kLeft), right = stamped(640, 480, kRight);
    ArViewInput input;
    input.left = &left;
    input.right = &right;
    input.ghost_q = model->named_configuration("qn").value();
    input.reported_q = input.ghost_q;
    const std::int64_t before = core::monotonic_ns();
    view->render(input);
    const ShownFrameCode shown_left = read_shown_frame_code(view->eye(0));
    EXPECT_EQ(shown_left.code, kLeft) << "k1 = " << kc.k1;
    EXPECT_GE(shown_left.shown_ns, before);
    EXPECT_EQ(read_shown_frame_code(view->eye(1)).code, kRight) << "k1 = " << kc.k1;
    // The strip is exactly the video's pixels: read back the eye and compare.
    const core::Image eye = view->eye(0).read_rgb();
    const vision::FrameCodeRect rect = *vision::frame_code_rect(640, 480);
    int differing = 0;
    for (int y = rect.y; y < rect.y + rect.height; ++y) {
      for (int x = rect.x * 3; x < (rect.x + rect.width) * 3; ++x) {
        differing += eye.row(y)[x] != left.row(y)[x];
      }
    }
    EXPECT_EQ(differing, 0) << "k1 = " << kc.k1;
  }
}

TEST_F(FrameCodeReadbackTest, NoVideoAWarpedVideoOrASmallEyeGiveNoCode) {
  const vision::Distortion barrel = vision::Distortion::plumb_bob(-0.3, 0.1, 0, 0, 0);
  auto view = ArView::create(
      *model, body, cameras_with(barrel), {},
      {.layout = StereoLayout::kSeparate, .overlay_mode = OverlayMode::kUndistorted});
  ASSERT_TRUE(view) << view.error().message;
  const core::Image left = stamped(640, 480, kLeft), right = stamped(640, 480, kRight);
  ArViewInput input;
  input.left = &left;
  input.right = &right;
  input.ghost_q = model->named_configuration("qn").value();
  view->render(input);
  // The undistorted picture moves the corner by pixels: no code (a wrong one is impossible).
  EXPECT_EQ(read_shown_frame_code(view->eye(0)).code, std::nullopt);
  input.mode = ViewMode::kVr;
  view->render(input);
  EXPECT_EQ(read_shown_frame_code(view->eye(0)).code, std::nullopt);

  auto small = ArView::create(*model, body, cameras_with({}, 160, 120), {},
                              {.layout = StereoLayout::kSeparate});
  ASSERT_TRUE(small) << small.error().message;
  const core::Image video(160, 120, 3);
  input = {};
  input.left = &video;
  input.right = &video;
  input.ghost_q = model->named_configuration("qn").value();
  small->render(input);
  EXPECT_EQ(read_shown_frame_code(small->eye(0)).code, std::nullopt);
}

}  // namespace
}  // namespace telear::render
