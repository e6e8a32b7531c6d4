// The AR view's input from a session's view (telear/view/ar_view_input.hpp): the predicted arm
// (issue 23) is passed on only when the session says to show it; a session without a robot
// state says why it predicts nothing, and rejects bad prediction options naming the field.

#include "telear/view/ar_view_input.hpp"

#include <gtest/gtest.h>

#include "test_util/test_util.hpp"

namespace telear::view {
namespace {

TEST(ArViewInput, ThePredictedArmIsDrawnOnlyWhenTheSessionShowsIt) {
  session::SessionView v;
  v.ghost_q = test::q6(0, 0.5, -0.5, 0, 0, 0);
  v.prediction.available = true;
  v.prediction.q = test::q6(0.1, 0.5, -0.5, 0, 0, 0);
  v.prediction.gripper = 0.25;
  EXPECT_EQ(ar_view_input(v).predicted_q.size(), 0);  // available, not shown: the state is fresh
  v.show_prediction = true;
  const render::ArViewInput input = ar_view_input(v);
  EXPECT_EQ(input.predicted_q, v.prediction.q);
  EXPECT_EQ(input.predicted_gripper, 0.25);
}

TEST(ArViewInput, TheArmAtCaptureIsPassedOnWhenTheSessionKnowsIt) {
  session::SessionView v;
  v.ghost_q = test::q6(0, 0.5, -0.5, 0, 0, 0);
  EXPECT_EQ(ar_view_input(v).capture_q.size(), 0);
  v.capture_arm = session::ArmAt{test::q6(0.2, 0.5, -0.5, 0, 0, 0), 0.5};
  const render::ArViewInput input = ar_view_input(v);
  EXPECT_EQ(input.capture_q, v.capture_arm->q);
  EXPECT_EQ(input.capture_gripper, 0.5);
}

TEST(ArViewInput, ASessionWithoutARobotStateSaysWhyItPredictsNothing) {
  session::SessionOptions options;
  options.robot.address = "127.0.0.1:1";  // never connected
  options.vision.address = "127.0.0.1:1";
  auto session = session::Session::create(test::puma560(), options);
  ASSERT_TRUE(session) << session.error().message;
  (*session)->update(0.05);
  const session::SessionView& v = (*session)->view();
  EXPECT_FALSE(v.prediction.available);
  EXPECT_EQ(v.prediction.summary(), "no prediction: no robot state yet");
  EXPECT_FALSE(v.show_prediction);
  EXPECT_EQ(ar_view_input(v).predicted_q.size(), 0);

  options.prediction.feedback_gain = -0.5;
  auto bad = session::Session::create(test::puma560(), options);
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().message, "session: arm predictor: feedback_gain -0.5 must be in [0, 1]");
  options.prediction = {};
  options.injected_state_delay_s = -1.0;
  bad = session::Session::create(test::puma560(), options);
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().message, "session: injected_state_delay_s must be >= 0");
}

}  // namespace
}  // namespace telear::view
