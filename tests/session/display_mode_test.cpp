#include "telear/session/display_mode.hpp"

#include <gtest/gtest.h>

namespace telear::session {
namespace {

// Frames captured every 1/30 s, delivered with `delay` s of latency, displayed at each arrival.
struct Stream {
  double period = 1.0 / 30.0;
  int frame = 0;
  double capture() const { return frame * period; }
};

DisplayModeOptions no_hold() {
  DisplayModeOptions options;
  options.fresh_hold_s = 0.0;  // the frame-count rule alone
  return options;
}

TEST(DisplayMode, StartsInVrAndGoesToArOnFreshVideo) {
  DisplayModeSelector selector(no_hold());
  EXPECT_EQ(selector.update(0.0, std::nullopt).mode, DisplayMode::kVR);
  EXPECT_EQ(selector.decision().reason, "no video yet");
  EXPECT_TRUE(selector.decision().stream_stopped);
  Stream s;
  for (; s.frame < 4; ++s.frame) selector.update(s.capture() + 0.05, s.capture());
  EXPECT_EQ(selector.mode(), DisplayMode::kVR);  // 4 of 5 fresh frames
  EXPECT_EQ(selector.decision().reason, "waiting for fresh video (4 of 5 frames under 150 ms)");
  selector.update(s.capture() + 0.05, s.capture());
  EXPECT_EQ(selector.mode(), DisplayMode::kAR);
  EXPECT_FALSE(selector.decision().frame_stale);
  EXPECT_NEAR(*selector.decision().frame_age, 0.05, 1e-12);
  EXPECT_EQ(selector.vr_to_ar_switches(), 1);
  EXPECT_EQ(selector.ar_to_vr_switches(), 0);
}

TEST(DisplayMode, InjectedDelaySwitchesToVrAndBackWithHysteresis) {
  DisplayModeSelector selector(no_hold());
  Stream s;
  double delay = 0.05;
  // The display runs at the frame rate; each new frame was captured `delay` s ago.
  auto step = [&] {
    ++s.frame;
    const double now = s.frame * s.period;
    return selector.update(now, now - delay);
  };
  for (int i = 0; i < 10; ++i) step();
  ASSERT_EQ(selector.mode(), DisplayMode::kAR);
  delay = 0.30;  // over the 250 ms threshold: VR at once
  const DisplayDecision late = step();
  EXPECT_EQ(late.mode, DisplayMode::kVR);
  EXPECT_TRUE(late.frame_stale);
  EXPECT_EQ(late.reason, "video late: frame age 300 ms over 250 ms");
  ASSERT_EQ(selector.ar_to_vr_switches(), 1);
  EXPECT_EQ(selector.switches().back().to, DisplayMode::kVR);
  EXPECT_NEAR(*selector.switches().back().frame_age, 0.30, 1e-9);
  // Back under the threshold but above 60 % of it (200 ms): stays in VR (hysteresis).
  delay = 0.20;
  for (int i = 0; i < 30; ++i) EXPECT_EQ(step().mode, DisplayMode::kVR);
  EXPECT_FALSE(selector.decision().frame_stale);  // not stale, yet not fresh enough
  // Fresh (100 ms): back to AR after 5 frames.
  delay = 0.10;
  for (int i = 0; i < 4; ++i) EXPECT_EQ(step().mode, DisplayMode::kVR);
  EXPECT_EQ(step().mode, DisplayMode::kAR);
  EXPECT_EQ(selector.vr_to_ar_switches(), 2);  // the start and this return
  EXPECT_EQ(selector.ar_to_vr_switches(), 1);
  // A late frame in between restarts the count.
  delay = 0.4;
  step();
  delay = 0.05;
  for (int i = 0; i < 3; ++i) step();
  delay = 0.4;
  step();
  delay = 0.05;
  for (int i = 0; i < 4; ++i) EXPECT_EQ(step().mode, DisplayMode::kVR);
  EXPECT_EQ(step().mode, DisplayMode::kAR);
}

// Issue 23, predict first: while the arm is predicted, late video stays in AR (marked stale,
// the prediction drawn over it); once prediction is impossible the AR / VR rule applies again.
TEST(DisplayMode, LateVideoStaysInArWhileTheArmIsPredicted) {
  DisplayModeSelector selector(no_hold());
  Stream s;
  double delay = 0.05;
  bool predicting = false;
  auto step = [&] {
    ++s.frame;
    const double now = s.frame * s.period;
    return selector.update(now, now - delay, predicting);
  };
  for (int i = 0; i < 10; ++i) step();
  ASSERT_EQ(selector.mode(), DisplayMode::kAR);
  EXPECT_FALSE(selector.decision().predicted);  // fresh video needs no prediction
  // A plan executes, the link becomes 400 ms late: AR, stale, predicted.
  predicting = true;
  delay = 0.40;
  for (int i = 0; i < 30; ++i) {
    const DisplayDecision& d = step();
    ASSERT_EQ(d.mode, DisplayMode::kAR) << d.reason;
    EXPECT_TRUE(d.frame_stale);
    EXPECT_TRUE(d.predicted);
  }
  EXPECT_EQ(selector.decision().reason,
            "video late: frame age 400 ms over 250 ms; the arm predicted ahead of it");
  EXPECT_EQ(selector.ar_to_vr_switches(), 0);
  // 30 frames at 30 fps held in AR by prediction (the first one switched nothing either).
  EXPECT_NEAR(selector.predicted_late_s(), 30 * s.period, 1e-9);
  // The plan ends, the video still late: prediction is impossible, VR at once.
  predicting = false;
  const DisplayDecision& ended = step();
  EXPECT_EQ(ended.mode, DisplayMode::kVR);
  EXPECT_FALSE(ended.predicted);
  EXPECT_EQ(ended.reason, "video late: frame age 400 ms over 250 ms");
  EXPECT_EQ(selector.ar_to_vr_switches(), 1);
  // A new plan under the same delay: back to AR at once, without waiting for fresh video.
  predicting = true;
  EXPECT_EQ(step().mode, DisplayMode::kAR);
  EXPECT_EQ(selector.vr_to_ar_switches(), 2);  // the start and this one
  // The video stops: VR even while predicting (the background is frozen).
  const double last = s.frame * s.period - delay;
  double now = s.frame * s.period;
  DisplayDecision d;
  for (int i = 0; i < 60; ++i) d = selector.update(now += 1.0 / 60, last, true);
  EXPECT_EQ(d.mode, DisplayMode::kVR);
  EXPECT_TRUE(d.stream_stopped);
  EXPECT_FALSE(d.predicted);
  // A forced mode is the operator's, not the prediction's.
  selector.set_preference(DisplayPreference::kAR);
  now += 0.02;
  EXPECT_FALSE(selector.update(now, now - 0.4, true).predicted);
}

TEST(DisplayMode, StoppedStreamShowsTheLastFrameAsStale) {
  DisplayModeSelector selector;
  Stream s;
  for (; s.frame < 10; ++s.frame) selector.update(s.capture() + 0.02, s.capture());
  ASSERT_EQ(selector.mode(), DisplayMode::kAR);
  const double last = s.capture() - s.period;
  // The display keeps updating at 60 Hz; no new frame arrives.
  double now = last + 0.02;
  DisplayDecision d;
  while (now < last + 1.0) {
    d = selector.update(now, last);
    now += 1.0 / 60;
  }
  EXPECT_EQ(d.mode, DisplayMode::kVR);
  EXPECT_TRUE(d.frame_stale);
  EXPECT_TRUE(d.stream_stopped);
  EXPECT_EQ(d.reason.rfind("video stopped: no new frame for ", 0), 0u) << d.reason;
  ASSERT_EQ(selector.ar_to_vr_switches(), 1);
  // It switched when the frame's age passed the threshold, before the stream timed out.
  EXPECT_EQ(selector.switches().back().reason.rfind("video late: frame age ", 0), 0u);
  EXPECT_GT(*selector.switches().back().frame_age, 0.25);
  EXPECT_LT(*selector.switches().back().frame_age, 0.25 + 1.0 / 60 + 1e-9);
}

TEST(DisplayMode, ForcedModesKeepTheMeasurementsAndHoldDelaysTheReturn) {
  DisplayModeOptions options;
  options.fresh_hold_s = 2.0;
  DisplayModeSelector selector(options);
  selector.set_preference(DisplayPreference::kAR);
  const DisplayDecision& d = selector.update(1.0, 0.5);  // 500 ms old
  EXPECT_EQ(d.mode, DisplayMode::kAR);
  EXPECT_TRUE(d.frame_stale);
  EXPECT_EQ(d.reason, "AR forced by the operator (video stale)");
  selector.set_preference(DisplayPreference::kVR);
  EXPECT_EQ(selector.update(1.1, 1.05).mode, DisplayMode::kVR);
  selector.set_preference(DisplayPreference::kAutomatic);
  // Late, then fresh frames: the return waits for the 2 s hold after the switch to VR.
  selector.update(1.2, 1.05);  // 150 ms, not late
  selector.update(1.6, 1.1);   // 500 ms: late
  ASSERT_EQ(selector.mode(), DisplayMode::kVR);
  int k = 0;  // fresh frames every 50 ms from t = 1.65: five of them by 1.85, but the hold
  double t = 1.6;
  while (selector.mode() == DisplayMode::kVR && k < 200) {
    t = 1.6 + 0.05 * ++k;
    selector.update(t, t - 0.02);
  }
  EXPECT_EQ(selector.mode(), DisplayMode::kAR);
  EXPECT_GE(k, 40);  // 1.6 + 2.0 s (rounding may add one frame)
  EXPECT_LE(k, 41);

  DisplayModeOptions bad;
  bad.late_threshold_s = -1;
  EXPECT_EQ(bad.validate().error().message,
            "display mode: late_threshold_s -1 must be positive and finite");
  bad = {};
  bad.fresh_fraction = 1.5;
  EXPECT_EQ(bad.validate().error().message, "display mode: fresh_fraction must be in (0, 1]");
}

}  // namespace
}  // namespace telear::session
