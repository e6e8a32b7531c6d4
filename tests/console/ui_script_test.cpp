#include "telear/console/ui_script.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "telear/console/ui_state.hpp"

namespace telear::console {
namespace {

using ::testing::HasSubstr;

TEST(UiScript, ParsesActionsWithUnits) {
  auto lines = parse_ui_script(
      "# a comment\n"
      "ghost joint 2 +5deg\n"
      "\n"
      "ghost cartesian tool z -20mm   # trailing comment\n"
      "ghost cartesian base rx 0.1rad\n"
      "ghost gripper close\n"
      "plan add 1.5 grasp the box\n"
      "wait 2.5\n"
      "wait-until idle 12\n"
      "real initialize qr\n"
      "real initialize 0,45,-90,0,30,0\n"
      "screenshot out.png\n",
      6);
  ASSERT_TRUE(lines) << lines.error().message;
  ASSERT_EQ(lines->size(), 10u);
  const auto& joint = std::get<UiAction>((*lines)[0].step);
  EXPECT_EQ((*lines)[0].line, 2);
  EXPECT_EQ(joint.kind, ActionKind::kGhostJoint);
  EXPECT_EQ(joint.index, 1);
  EXPECT_NEAR(joint.value, 5 * M_PI / 180, 1e-12);
  const auto& cart = std::get<UiAction>((*lines)[1].step);
  EXPECT_EQ(cart.frame, core::MotionFrame::kTool);
  EXPECT_NEAR(cart.dX.z(), -0.02, 1e-12);
  EXPECT_NEAR(std::get<UiAction>((*lines)[2].step).dM.x(), 0.1, 1e-12);
  EXPECT_EQ(std::get<UiAction>((*lines)[3].step).value, 0.0);
  const auto& add = std::get<UiAction>((*lines)[4].step);
  EXPECT_EQ(add.value, 1.5);
  EXPECT_EQ(add.text, "grasp the box");
  EXPECT_EQ(std::get<WaitFor>((*lines)[5].step).seconds, 2.5);
  EXPECT_EQ(std::get<WaitUntil>((*lines)[6].step).timeout_s, 12.0);
  EXPECT_EQ(std::get<UiAction>((*lines)[7].step).text, "qr");
  EXPECT_NEAR(std::get<UiAction>((*lines)[8].step).q[2], -M_PI / 2, 1e-12);
  EXPECT_EQ((*lines)[9].line, 12);
}

TEST(UiScript, ErrorsNameTheLine) {
  auto unknown = parse_ui_script("ghost joint 1 5\n\nghots joint 1 5\n", 6, "script 's.txt'");
  ASSERT_FALSE(unknown);
  EXPECT_THAT(unknown.error().message,
              HasSubstr("script 's.txt', line 3: ghots joint 1 5: unknown command 'ghots'"));

  auto joint = parse_ui_script("ghost joint 7 +5deg\n", 6);
  ASSERT_FALSE(joint);
  EXPECT_THAT(joint.error().message, HasSubstr("line 1"));
  EXPECT_THAT(joint.error().message, HasSubstr("joint 7 out of range 1..6"));

  auto number = parse_ui_script("wait\nwait soon\n", 6);
  ASSERT_FALSE(number);
  EXPECT_THAT(number.error().message, HasSubstr("line 1: wait: usage: wait SECONDS"));

  auto value = parse_ui_script("plan add 1\nwait x\n", 6);
  ASSERT_FALSE(value);
  EXPECT_THAT(value.error().message, HasSubstr("line 2: wait x: wait: 'x' is not a number"));

  auto frame = parse_ui_script("ghost cartesian world z 1\n", 6);
  ASSERT_FALSE(frame);
  EXPECT_THAT(frame.error().message, HasSubstr("frame 'world': base, wrist or tool"));

  auto condition = parse_ui_script("wait-until forever\n", 6);
  ASSERT_FALSE(condition);
  EXPECT_THAT(condition.error().message,
              HasSubstr("condition 'forever': idle, connected, disconnected, video, preview-end, "
                        "in-control or ar"));
  auto ar = parse_ui_script("wait-until ar 5\n", 6);
  ASSERT_TRUE(ar) << ar.error().message;
  EXPECT_EQ(std::get<WaitUntil>((*ar)[0].step).condition, Condition::kAr);

  auto q = parse_ui_script("real initialize 1,2,3\n", 6);
  ASSERT_FALSE(q);
  EXPECT_THAT(q.error().message, HasSubstr("6 joint values needed, got 3"));

  auto plots = parse_ui_script("view plots off\nview plots maybe\n", 6);
  ASSERT_FALSE(plots);
  EXPECT_THAT(plots.error().message, HasSubstr("line 2: view plots maybe: view plots on|off"));

  auto missing = load_ui_script("/nonexistent/script.txt", 6);
  ASSERT_FALSE(missing);
  EXPECT_THAT(missing.error().message, HasSubstr("cannot be read"));
}

// Issue 23: the predicted arm's toggle, from a script line to the AR view's option.
TEST(UiScript, ViewPredictedTogglesThePredictedArm) {
  auto lines = parse_ui_script("view predicted off\nview predicted on\n", 6);
  ASSERT_TRUE(lines) << lines.error().message;
  const auto& off = std::get<UiAction>((*lines)[0].step);
  EXPECT_EQ(off.kind, ActionKind::kViewPredicted);
  EXPECT_EQ(off.value, 0.0);
  EXPECT_EQ(std::get<UiAction>((*lines)[1].step).value, 1.0);
  UiState ui;
  EXPECT_TRUE(with_view_settings({}, ui).show_predicted);
  ui.show_predicted = false;
  EXPECT_FALSE(with_view_settings({}, ui).show_predicted);

  auto bad = parse_ui_script("view predicted maybe\n", 6);
  ASSERT_FALSE(bad);
  EXPECT_THAT(bad.error().message, HasSubstr("view predicted maybe: view predicted on|off"));

  // ... and the arm at the frame's capture, off until asked for.
  auto capture = parse_ui_script("view capture on\n", 6);
  ASSERT_TRUE(capture) << capture.error().message;
  EXPECT_EQ(std::get<UiAction>((*capture)[0].step).kind, ActionKind::kViewCapture);
  EXPECT_EQ(std::get<UiAction>((*capture)[0].step).value, 1.0);
  EXPECT_FALSE(with_view_settings({}, UiState{}).show_capture_arm);
  ui.show_capture_arm = true;
  EXPECT_TRUE(with_view_settings({}, ui).show_capture_arm);
  bad = parse_ui_script("view capturing on\n", 6);
  ASSERT_FALSE(bad);
  EXPECT_THAT(bad.error().message,
              HasSubstr("unknown view setting 'capturing' (layout, style, segments, opacity, "
                        "video, mode, reported, predicted, capture, plots)"));
}

}  // namespace
}  // namespace telear::console
