// The operator's stereo view (telear/render/ar_view.hpp): video under the ghost in AR, the virtual
// scene in VR, the status frame that tells live from virtual from stale, the predicted arm.
#include "telear/render/ar_view.hpp"

#include <gtest/gtest.h>

#include "gl_test_util.hpp"
#include "telear/core/arm_body.hpp"
#include "test_util/test_util.hpp"

namespace telear::render {
namespace {

class ArViewTest : public test::GlTest {
 protected:
  void SetUp() override {
    test::GlTest::SetUp();
    model = telear::test::puma560();
    auto description = core::body_description_for(*model);
    ASSERT_TRUE(description) << description.error().message;
    body = core::build_arm_body(*description);
    const Eigen::Vector3d target(0.3, -0.1, 0.4);
    cameras.left = vision::look_at_camera(160, 120, 0.9, {2.0, -0.5, 1.0}, target, {0, 0, 1});
    cameras.right = vision::look_at_camera(160, 120, 0.9, {2.0, -0.44, 1.0}, target, {0, 0, 1});
    video = core::Image(160, 120, 3);
    for (size_t i = 0; i < video.pixels.size(); i += 3) {
      video.pixels[i] = 200;  // a red "video"
      video.pixels[i + 1] = 30;
      video.pixels[i + 2] = 30;
    }
  }

  ArViewInput input_at(const Eigen::VectorXd& q) const {
    ArViewInput input;
    input.left = &video;
    input.right = &video;
    input.ghost_q = q;
    return input;
  }

  core::RobotModelPtr model;
  core::ArmBody body;
  vision::StereoCameraModel cameras;
  core::Image video;
};

const Eigen::Vector3i kRed(200, 30, 30);

TEST_F(ArViewTest, ArModeDrawsTheGhostOverTheVideoAndSaysLive) {
  auto view = ArView::create(*model, body, cameras, {make_floor(3.0f, 12)},
                             {.layout = StereoLayout::kSideBySide});
  ASSERT_TRUE(view) << view.error().message;
  view->render(input_at(model->named_configuration("qn").value()));
  EXPECT_EQ(view->status(), ViewStatus::kLive);
  const core::Image composed = view->read_composed_rgb();
  ASSERT_EQ(composed.width, 320);
  ASSERT_EQ(composed.height, 120);
  // The video fills the eye; the ghost covers part of it, the floor is not drawn in AR.
  const long covered = test::count_covered(composed, kRed);
  EXPECT_GT(covered, 500);
  EXPECT_LT(covered, 320 * 120 / 2);
  EXPECT_FALSE(test::differs(composed, 20, 100, kRed)) << "video under the floor's place";
  // Status frame: green on the border.
  const std::uint8_t* corner = &composed.pixels[(1 * composed.width + 1) * 3];
  EXPECT_GT(corner[1], 150);
  EXPECT_LT(corner[0], 80);
}

TEST_F(ArViewTest, VrModeDrawsTheVirtualSceneWithoutTheVideo) {
  auto view = ArView::create(*model, body, cameras, {make_floor(3.0f, 12)},
                             {.layout = StereoLayout::kTopBottom});
  ASSERT_TRUE(view) << view.error().message;
  ArViewInput input = input_at(model->named_configuration("qn").value());
  input.mode = ViewMode::kVr;
  input.reported_q = input.ghost_q;
  view->render(input);
  EXPECT_EQ(view->status(), ViewStatus::kVirtual);
  const core::Image composed = view->read_composed_rgb();
  ASSERT_EQ(composed.width, 160);
  ASSERT_EQ(composed.height, 240);
  // No pixel of the red video is left inside the border.
  long red = 0;
  for (int y = 8; y < composed.height - 8; ++y) {
    for (int x = 8; x < composed.width - 8; ++x) red += !test::differs(composed, x, y, kRed, 20);
  }
  EXPECT_EQ(red, 0);
  const std::uint8_t* corner = &composed.pixels[(1 * composed.width + 1) * 3];
  EXPECT_GT(corner[0], 200);  // amber
  EXPECT_GT(corner[1], 120);
  EXPECT_LT(corner[2], 60);
}

TEST_F(ArViewTest, StaleOrMismatchedVideoIsMarkedStaleNeverLive) {
  auto view = ArView::create(*model, body, cameras, {}, {.layout = StereoLayout::kSeparate});
  ASSERT_TRUE(view) << view.error().message;
  ArViewInput input = input_at(model->named_configuration("qz").value());
  input.stale = true;
  view->render(input);
  EXPECT_EQ(view->status(), ViewStatus::kStale);
  core::Image eye = view->eye(0).read_rgb();
  const std::uint8_t* corner = &eye.pixels[(1 * eye.width + 1) * 3];
  EXPECT_GT(corner[0], 200);  // red frame
  EXPECT_LT(corner[1], 60);
  // A frame of the wrong size is not drawn at all.
  core::Image small(80, 60, 3);
  input.stale = false;
  input.left = &small;
  view->render(input);
  EXPECT_EQ(view->status(), ViewStatus::kStale);
  eye = view->eye(1).read_rgb();
  EXPECT_TRUE(test::differs(eye, 20, 100, kRed)) << "the right eye's video was drawn alone";
}

TEST_F(ArViewTest, TheReportedGhostIsDrawnWhereTheRobotIs) {
  auto view = ArView::create(*model, body, cameras, {}, {.layout = StereoLayout::kSeparate});
  ASSERT_TRUE(view) << view.error().message;
  const Eigen::VectorXd qz = model->named_configuration("qz").value();
  Eigen::VectorXd away = qz;
  away[0] += 1.2;
  ArViewInput input = input_at(qz);
  view->render(input);
  const long ghost_only = test::count_covered(view->eye(0).read_rgb(), kRed);
  input.reported_q = away;
  view->render(input);
  const long both = test::count_covered(view->eye(0).read_rgb(), kRed);
  EXPECT_GT(both, ghost_only + 100);
  ArViewOptions options = view->options();
  options.show_reported_ghost = false;
  view->set_options(options);
  view->render(input);
  EXPECT_EQ(test::count_covered(view->eye(0).read_rgb(), kRed), ghost_only);
}

// Pixels clearly red (red well above green and blue): the contact highlight, not the ghost's
// blue tint nor the grey VR background.
long count_contact_red(const core::Image& image) {
  long n = 0;
  for (std::size_t i = 0; i + 2 < image.pixels.size(); i += 3) {
    const int r = image.pixels[i], g = image.pixels[i + 1], b = image.pixels[i + 2];
    if (r > g + 50 && r > b + 50) ++n;
  }
  return n;
}

TEST_F(ArViewTest, GhostLinksInContactAreDrawnRed) {
  auto view = ArView::create(*model, body, cameras, {},
                             {.layout = StereoLayout::kSeparate, .status_border_px = 0});
  ASSERT_TRUE(view) << view.error().message;
  ArViewInput input;
  input.mode = ViewMode::kVr;  // no (red) video under the ghost
  input.ghost_q = model->named_configuration("qn").value();
  view->render(input);
  EXPECT_EQ(count_contact_red(view->eye(0).read_rgb()), 0);

  input.ghost_highlight_frames = {3};  // the forearm
  view->render(input);
  const long forearm = count_contact_red(view->eye(0).read_rgb());
  EXPECT_GT(forearm, 100);
  input.ghost_highlight_frames = {0, 1, 2, 3, 4, 5, 6};  // the whole arm: more of it is red
  view->render(input);
  EXPECT_GT(count_contact_red(view->eye(0).read_rgb()), forearm + 100);
  input.ghost_highlight_frames.clear();
  view->render(input);
  EXPECT_EQ(count_contact_red(view->eye(0).read_rgb()), 0);
}

// Pixels of the predicted arm's magenta: red and blue well above green.
long count_magenta(const core::Image& image) {
  long n = 0;
  for (std::size_t i = 0; i + 2 < image.pixels.size(); i += 3) {
    const int r = image.pixels[i], g = image.pixels[i + 1], b = image.pixels[i + 2];
    if (r > g + 80 && b > g + 80) ++n;
  }
  return n;
}

TEST_F(ArViewTest, ThePredictedArmIsAMagentaWireFrameInBothModesAndCanBeHidden) {
  auto view = ArView::create(*model, body, cameras, {},
                             {.layout = StereoLayout::kSeparate, .status_border_px = 0});
  ASSERT_TRUE(view) << view.error().message;
  const Eigen::VectorXd qz = model->named_configuration("qz").value();
  Eigen::VectorXd ahead = qz;
  ahead[0] += 1.0;  // where the arm is now, away from the ghost and the reported arm
  for (const ViewMode mode : {ViewMode::kAr, ViewMode::kVr}) {
    ArViewInput input = input_at(qz);
    input.mode = mode;
    input.reported_q = qz;
    view->render(input);
    EXPECT_EQ(count_magenta(view->eye(0).read_rgb()), 0);
    input.predicted_q = ahead;
    view->render(input);
    const long drawn = count_magenta(view->eye(0).read_rgb());
    EXPECT_GT(drawn, 50) << (mode == ViewMode::kAr ? "AR" : "VR");
    // A wire-frame: its edges, far fewer pixels than the solid ghost covers.
    EXPECT_LT(drawn, 160 * 120 / 10);
    ArViewOptions hidden = view->options();
    hidden.show_predicted = false;
    view->set_options(hidden);
    view->render(input);
    EXPECT_EQ(count_magenta(view->eye(0).read_rgb()), 0);
    hidden.show_predicted = true;
    view->set_options(hidden);
  }
}

// Near-white pixels: the arm at the frame's capture (its default colour).
long count_white(const core::Image& image) {
  long n = 0;
  for (std::size_t i = 0; i + 2 < image.pixels.size(); i += 3) {
    if (image.pixels[i] > 225 && image.pixels[i + 1] > 225 && image.pixels[i + 2] > 225) ++n;
  }
  return n;
}

TEST_F(ArViewTest, TheArmAtCaptureIsAWhiteWireFrameOverTheVideoWhenAskedFor) {
  auto view = ArView::create(*model, body, cameras, {},
                             {.layout = StereoLayout::kSeparate, .status_border_px = 0});
  ASSERT_TRUE(view) << view.error().message;
  const Eigen::VectorXd qz = model->named_configuration("qz").value();
  Eigen::VectorXd then = qz;
  then[0] -= 1.0;  // away from the ghost
  ArViewInput input = input_at(qz);
  input.capture_q = then;
  view->render(input);
  const long before = count_white(view->eye(0).read_rgb());
  ArViewOptions shown = view->options();
  shown.show_capture_arm = true;  // off by default
  view->set_options(shown);
  view->render(input);
  const long drawn = count_white(view->eye(0).read_rgb()) - before;
  EXPECT_GT(drawn, 50);
  EXPECT_LT(drawn, 160 * 120 / 10);  // a wire-frame's edges
  // VR has no video for it to sit on: not drawn.
  input.mode = ViewMode::kVr;
  view->render(input);
  const long vr = count_white(view->eye(0).read_rgb());
  input.capture_q.resize(0);
  view->render(input);
  EXPECT_EQ(vr, count_white(view->eye(0).read_rgb()));
}

}  // namespace
}  // namespace telear::render
