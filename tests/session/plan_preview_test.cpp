#include "telear/session/plan_preview.hpp"

#include <gtest/gtest.h>

#include "telear/session/plan.hpp"
#include "test_util/test_util.hpp"

namespace telear::session {
namespace {

core::Trajectory two_point_trajectory() {
  Eigen::VectorXd a = Eigen::VectorXd::Zero(6), b = Eigen::VectorXd::Zero(6);
  b[0] = 0.5;
  auto t = core::Trajectory::create(*test::puma560(), {{a, 0.0, 1.0}, {b, 2.0, 0.0}});
  EXPECT_TRUE(t.ok());
  return *t;
}

TEST(PlanPreview, PlaysPausesAndStopsAtTheEnd) {
  PlanPreview preview(two_point_trajectory());
  const double d = preview.duration();
  EXPECT_NEAR(d, 2.0, 1e-12);  // stretched by the min_duration
  EXPECT_FALSE(preview.playing());
  EXPECT_EQ(preview.advance(0.5).time, 0.0);  // paused: no motion
  preview.play();
  PreviewFrame f = preview.advance(0.5);
  EXPECT_DOUBLE_EQ(f.time, 0.5);
  EXPECT_TRUE(f.playing);
  EXPECT_EQ(f.q, preview.trajectory().sample(0.5).q);
  EXPECT_EQ(f.gripper, 1.0);
  EXPECT_EQ(f.waypoint, 0);
  preview.pause();
  EXPECT_DOUBLE_EQ(preview.advance(1.0).time, 0.5);
  preview.play();
  f = preview.advance(10.0);
  EXPECT_DOUBLE_EQ(f.time, d);
  EXPECT_TRUE(f.at_end);
  EXPECT_FALSE(f.playing);
  EXPECT_EQ(f.gripper, 0.0);
  EXPECT_EQ(f.waypoint, 1);
  EXPECT_DOUBLE_EQ(f.q[0], 0.5);  // exactly the last waypoint
  preview.play();                 // from the end: starts again
  EXPECT_DOUBLE_EQ(preview.time(), 0.0);
  EXPECT_DOUBLE_EQ(preview.advance(-1.0).time, 0.0);  // negative dt ignored
}

TEST(PlanPreview, LoopsScrubsAndChangesSpeed) {
  PlanPreview preview(two_point_trajectory(), {.loop = true, .speed = 2.0});
  preview.play();
  EXPECT_DOUBLE_EQ(preview.advance(0.5).time, 1.0);
  PreviewFrame f = preview.advance(0.75);  // 1.0 + 1.5 = 2.5 -> 0.5 after wrapping
  EXPECT_NEAR(f.time, 0.5, 1e-12);
  EXPECT_TRUE(f.playing);
  EXPECT_FALSE(f.at_end);
  preview.pause();
  preview.seek(1.25);
  EXPECT_DOUBLE_EQ(preview.current().time, 1.25);
  preview.seek(99.0);
  EXPECT_DOUBLE_EQ(preview.time(), preview.duration());
  preview.seek(-3.0);
  EXPECT_DOUBLE_EQ(preview.time(), 0.0);
  ASSERT_TRUE(preview.set_speed(0.5).ok());
  Status bad = preview.set_speed(0.0);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().message, "preview speed 0 is outside (0, 16]");
  EXPECT_EQ(preview.speed(), 0.5);
  preview.play();
  EXPECT_DOUBLE_EQ(preview.advance(1.0).time, 0.5);
}

TEST(PlanPreview, SingleWaypointPlanHasZeroDuration) {
  Plan plan(test::puma560());
  ASSERT_TRUE(plan.add({Eigen::VectorXd::Zero(6)}).ok());
  PlanPreview preview(*plan.trajectory(), {.loop = true});
  preview.play();
  const PreviewFrame f = preview.advance(1.0);
  EXPECT_EQ(f.time, 0.0);
  EXPECT_FALSE(f.playing);
  EXPECT_EQ(f.q, Eigen::VectorXd::Zero(6));
}

}  // namespace
}  // namespace telear::session
