#include "telear/session/plan.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "telear/session/ghost_arm.hpp"
#include "test_util/temp_dir.hpp"
#include "test_util/test_util.hpp"

namespace telear::session {
namespace {

using test::q6;

Plan three_waypoints() {
  Plan plan(test::puma560());
  EXPECT_TRUE(plan.add({q6(0, 0.5, -1.2, 0, 0.7, 0), 0.0, 1.0, "approach"}).ok());
  EXPECT_TRUE(plan.add({q6(0.2, 0.6, -1.1, 0, 0.5, 0), 0.0, 0.0, "grasp"}).ok());
  EXPECT_TRUE(plan.add({q6(0.2, 0.6, -1.1, 0, 0.5, 0), 1.5, std::nullopt, "dwell"}).ok());
  return plan;
}

TEST(Plan, RecordsGhostPosesAndEdits) {
  GhostArm ghost(test::puma560());
  Plan plan(test::puma560());
  ASSERT_TRUE(plan.add_from(ghost, 0.0, "start").ok());
  ghost.apply(core::JointIncrement{0, 0.3});
  ASSERT_TRUE(ghost.set_gripper(0.0).ok());
  ASSERT_TRUE(plan.add_from(ghost, 2.0, "close").ok());
  ASSERT_EQ(plan.size(), 2u);
  EXPECT_EQ(plan.waypoint(1).q, ghost.q());
  EXPECT_EQ(plan.waypoint(1).gripper, 0.0);
  EXPECT_EQ(plan.waypoint(1).min_duration, 2.0);
  ASSERT_TRUE(plan.add_from(ghost, 0.0, "middle", false, 1).ok());
  EXPECT_EQ(plan.waypoint(1).label, "middle");
  EXPECT_FALSE(plan.waypoint(1).gripper.has_value());

  ASSERT_TRUE(plan.move(0, 2).ok());
  EXPECT_EQ(plan.waypoint(0).label, "middle");
  EXPECT_EQ(plan.waypoint(2).label, "start");
  ASSERT_TRUE(plan.remove(0).ok());
  EXPECT_EQ(plan.waypoint(0).label, "close");
  ASSERT_TRUE(plan.set_min_duration(1, 0.5).ok());
  EXPECT_EQ(plan.waypoint(1).min_duration, 0.5);
  ASSERT_TRUE(plan.set_gripper(1, 1.0).ok());
  EXPECT_EQ(plan.waypoint(1).gripper, 1.0);
}

TEST(Plan, RejectedEditsChangeNothingAndSayWhy) {
  Plan plan = three_waypoints();
  Status remove = plan.remove(5);
  ASSERT_FALSE(remove.ok());
  EXPECT_EQ(remove.error().message, "remove: no waypoint[5] (the plan has 3 waypoints)");
  Status move = plan.move(0, 3);
  ASSERT_FALSE(move.ok());
  EXPECT_EQ(move.error().message, "move: no waypoint[3] (the plan has 3 waypoints)");
  Status duration = plan.set_min_duration(2, -1.0);
  ASSERT_FALSE(duration.ok());
  EXPECT_EQ(duration.error().message,
            "set duration: waypoint[2]: min_duration -1 s is outside 0..3600 s");
  EXPECT_EQ(plan.waypoint(2).min_duration, 1.5);
  Status gripper = plan.set_gripper(0, 2.0);
  ASSERT_FALSE(gripper.ok());
  EXPECT_EQ(gripper.error().message,
            "set gripper: waypoint[0]: gripper opening 2 is outside 0 (closed) .. 1 (open)");
  Status size = plan.add({Eigen::VectorXd::Zero(5)});
  ASSERT_FALSE(size.ok());
  EXPECT_EQ(size.error().message, "add: waypoint[3]: expected 6 joint values, got 5");
  Status limit = plan.add({q6(0, 0, 3.0, 0, 0, 0)}, 0);
  ASSERT_FALSE(limit.ok());
  EXPECT_EQ(limit.error().message,
            "add: waypoint[0]: joint 3 (elbow) would be at 171.89 deg, beyond its upper limit of "
            "135.00 deg");
  Status nan = plan.add({q6(0, std::nan(""), 0, 0, 0, 0)});
  ASSERT_FALSE(nan.ok());
  EXPECT_EQ(nan.error().message, "add: waypoint[3]: joint 2 (shoulder) is not finite (NaN or inf)");
  Status at = plan.add({q6(0, 0, 0, 0, 0, 0)}, 7);
  ASSERT_FALSE(at.ok());
  EXPECT_EQ(at.error().message, "add: cannot insert at waypoint[7] (the plan has 3 waypoints)");
  EXPECT_EQ(plan.size(), 3u);
  Status scales = plan.set_scales(0.0, 1.0);
  ASSERT_FALSE(scales.ok());
  EXPECT_EQ(scales.error().message, "velocity_scale 0 is outside (0, 1]");
}

TEST(Plan, TimesAndSamplesLikeTheCoreTrajectory) {
  Plan plan = three_waypoints();
  ASSERT_TRUE(plan.set_scales(0.5, 0.5).ok());
  auto trajectory = plan.trajectory();
  ASSERT_TRUE(trajectory.ok()) << trajectory.error().message;
  auto reference =
      core::Trajectory::create(plan.model(), plan.joint_waypoints(), plan.trajectory_options());
  ASSERT_TRUE(reference.ok());
  EXPECT_DOUBLE_EQ(trajectory->duration(), reference->duration());
  EXPECT_EQ(trajectory->waypoint_times().size(), 3u);
  // The dwell lasts its min_duration; the gripper closes on arrival at "grasp".
  EXPECT_NEAR(trajectory->waypoint_times()[2] - trajectory->waypoint_times()[1], 1.5, 1e-12);
  EXPECT_EQ(trajectory->gripper_at(trajectory->waypoint_times()[1]), 0.0);
  // Half speed takes longer than full speed.
  Plan fast = three_waypoints();
  EXPECT_GT(trajectory->duration(), fast.trajectory()->duration());

  auto sampled = plan.timed_waypoints(100.0);
  ASSERT_TRUE(sampled.ok()) << sampled.error().message;
  EXPECT_TRUE(core::validate_timed_waypoints(plan.model(), *sampled).ok());
  EXPECT_DOUBLE_EQ(sampled->times.back(), trajectory->duration());

  Plan empty(test::puma560());
  auto none = empty.trajectory();
  ASSERT_FALSE(none.ok());
  EXPECT_EQ(none.error().message, "the plan is empty; add at least one waypoint");
}

TEST(Plan, YamlRoundTrip) {
  Plan plan = three_waypoints();
  ASSERT_TRUE(plan.set_scales(0.5, 0.25).ok());
  PlanWaypoint passed = plan.waypoint(1);
  passed.via = true;
  ASSERT_TRUE(plan.replace(1, passed).ok());
  test_files::TempDir tmp("plan");
  const std::string path = tmp.file("plan.yaml");
  ASSERT_TRUE(plan.save(path).ok());
  auto loaded = Plan::load(test::puma560(), path);
  std::remove(path.c_str());
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  ASSERT_EQ(loaded->size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(loaded->waypoint(i).q, plan.waypoint(i).q);  // bit-exact (17 digits)
    EXPECT_EQ(loaded->waypoint(i).gripper, plan.waypoint(i).gripper);
    EXPECT_EQ(loaded->waypoint(i).min_duration, plan.waypoint(i).min_duration);
    EXPECT_EQ(loaded->waypoint(i).label, plan.waypoint(i).label);
    EXPECT_EQ(loaded->waypoint(i).via, plan.waypoint(i).via);
  }
  EXPECT_TRUE(loaded->waypoint(1).via);
  EXPECT_TRUE(loaded->joint_waypoints()[1].via);
  EXPECT_EQ(loaded->trajectory_options().velocity_scale, 0.5);
  EXPECT_EQ(loaded->trajectory_options().acceleration_scale, 0.25);
}

std::string load_error(const std::string& text) {
  auto plan = Plan::from_yaml(test::puma560(), text, "p.yaml");
  EXPECT_FALSE(plan.ok()) << text;
  return plan ? std::string() : plan.error().message;
}

TEST(Plan, UntrustedFilesGiveErrorsNamingWaypointAndField) {
  const std::string head = "robot: puma560\nwaypoints:\n";
  EXPECT_EQ(load_error("robot: kuka\nwaypoints: []\n"),
            "plan 'p.yaml': robot: the plan is for 'kuka', not for the loaded model 'puma560'");
  EXPECT_EQ(load_error("waypoints: []\n"),
            "plan 'p.yaml': robot: missing (the model's name, e.g. robot: puma560)");
  EXPECT_EQ(load_error(head + "  - {q_rad: [0, 0, 0, 0, 0]}\n"),
            "plan 'p.yaml': waypoint[0].q_rad: expected 6 numbers, got 5");
  EXPECT_EQ(load_error(head + "  - {q_rad: [0, 0, 0, 0, 0, 0]}\n  - {q_rad: [0, 0, x, 0, 0, 0]}\n"),
            "plan 'p.yaml': waypoint[1].q_rad[2]: must be a number, got 'x'");
  EXPECT_EQ(load_error(head + "  - {q_rad: [0, 0, 0, 0, 0, 0], gripper: .nan}\n"),
            "plan 'p.yaml': waypoint[0].gripper: must be finite, got .nan");
  EXPECT_EQ(load_error(head + "  - {q_rad: [0, 0, 0, 0, 0, 0], gripper: 3}\n"),
            "plan 'p.yaml': waypoint[0]: gripper opening 3 is outside 0 (closed) .. 1 (open)");
  EXPECT_EQ(load_error(head + "  - {q_rad: [0, 0, 2.5, 0, 0, 0]}\n"),
            "plan 'p.yaml': waypoint[0]: joint 3 (elbow) would be at 143.24 deg, beyond its upper "
            "limit of 135.00 deg");
  EXPECT_EQ(load_error(head + "  - {q_deg: [0, 0, 0, 0, 0, 0]}\n"),
            "plan 'p.yaml': waypoint[0].q_deg: unknown key (known: cartesian, gripper, label, "
            "min_duration_s, q_rad, via)");
  EXPECT_EQ(load_error(head + "  - {q_rad: [0, 0, 0, 0, 0, 0], via: maybe}\n"),
            "plan 'p.yaml': waypoint[0].via: must be true or false");
  EXPECT_EQ(load_error(head + "  - {q_rad: [0, 0, 0, 0, 0, 0], min_duration_s: -2}\n"),
            "plan 'p.yaml': waypoint[0]: min_duration -2 s is outside 0..3600 s");
  EXPECT_EQ(load_error("robot: puma560\nvelocity_scale: 2\nwaypoints: []\n"),
            "plan 'p.yaml': velocity_scale 2 is outside (0, 1]");
  EXPECT_EQ(load_error("[1, 2"), load_error("[1, 2"));  // deterministic
  EXPECT_EQ(load_error("[1, 2").rfind("plan 'p.yaml': not valid YAML at line 1: ", 0), 0u);
  auto missing = Plan::load(test::puma560(), "/nonexistent/plan.yaml");
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().message, "plan '/nonexistent/plan.yaml': cannot be opened");
  auto empty = Plan::from_yaml(test::puma560(), "robot: puma560\nwaypoints:\n", "p.yaml");
  ASSERT_TRUE(empty.ok());
  EXPECT_TRUE(empty->empty());
}

}  // namespace
}  // namespace telear::session
