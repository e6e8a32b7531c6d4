// Where the demo's registration capture starts (include/telear/lab/capture_start.hpp), on the
// UR-type arm whose demo failed there (issue 26): the simulator's observations, the arm's own
// robot file and workspace, the robot server's collision checker.

#include "telear/lab/capture_start.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "telear/core/robot_loader.hpp"
#include "telear/core/trajectory.hpp"
#include "telear/geometry/carried_objects.hpp"
#include "telear/geometry/collision_checker.hpp"
#include "telear/geometry/robot_assets.hpp"
#include "telear/geometry/trajectory_collision.hpp"
#include "telear/geometry/workspace_meshes.hpp"
#include "telear/sim/marker_observations.hpp"
#include "test_util/test_util.hpp"

namespace telear::lab {
namespace {

using ::testing::HasSubstr;

struct Ur6 {
  geometry::RobotAssets robot;
  core::Workspace workspace;
  Eigen::VectorXd ready;
  vision::RegistrationObservations observations;  // the demo's seed
};

Ur6 load_ur6(bool collision_free, int configurations) {
  Ur6 ur6;
  auto robot = geometry::load_robot_assets({"ur6", "", {}});
  EXPECT_TRUE(robot.ok()) << robot.error().message;
  ur6.robot = std::move(robot).value();
  auto workspace = geometry::load_workspace(core::default_workspace_file("ur6"));
  EXPECT_TRUE(workspace.ok()) << workspace.error().message;
  ur6.workspace = std::move(workspace).value();
  ur6.ready = *ur6.robot.model()->named_configuration("ready");
  sim::MarkerObservationsOptions options;
  options.rig_file = test::data_path("rigs/ur6_rig.yaml");
  options.robot = "ur6";
  options.configurations = configurations;
  options.supersample = 1;
  options.seed = 1;  // the demo's
  options.collision_free = collision_free;
  auto observed = sim::simulate_marker_observations(options);
  EXPECT_TRUE(observed.ok()) << observed.error().message;
  ur6.observations = std::move(observed->observations);
  return ur6;
}

const vision::ObservedConfiguration* first_seen_by_both(const vision::RegistrationObservations& o) {
  for (const auto& c : o.configurations) {
    if (!c.left_pixels.empty() && !c.right_pixels.empty()) return &c;
  }
  return nullptr;
}

// The demo's pipeline draws its observations free of contact (sim::MarkerObservationsOptions::
// collision_free): the capture starts at one whose straight move to the ready pose is free too.
TEST(CaptureStart, StartsWhereTheMoveToReadyIsFree) {
  const Ur6 ur6 = load_ur6(true, 20);
  auto start =
      capture_start_pose(ur6.observations, ur6.robot.description, ur6.workspace, ur6.ready);
  ASSERT_TRUE(start.ok()) << start.error().message;
  auto checker = geometry::make_collision_checker(ur6.robot.description,
                                                  geometry::static_obstacles(ur6.workspace));
  ASSERT_TRUE(checker.ok()) << checker.error().message;
  EXPECT_TRUE(checker->check(*start).collision_free());
  auto move = core::Trajectory::create(*ur6.robot.model(), {{*start}, {ur6.ready}});
  ASSERT_TRUE(move.ok());
  auto report = geometry::check_trajectory(*checker, *move);
  ASSERT_TRUE(report.ok());
  EXPECT_TRUE(report->collision_free());
}

// Without collision_free, the first view of the marker (where the demo started before issue 26)
// has the arm in itself: the server would refuse every move from there.
TEST(CaptureStart, SaysWhyThereIsNowhereToStart) {
  const Ur6 ur6 = load_ur6(false, 8);
  const auto* first = first_seen_by_both(ur6.observations);
  ASSERT_NE(first, nullptr);
  auto checker = geometry::make_collision_checker(ur6.robot.description,
                                                  geometry::static_obstacles(ur6.workspace));
  ASSERT_TRUE(checker.ok()) << checker.error().message;
  const geometry::CollisionReport at_first = checker->check(first->q);
  ASSERT_FALSE(at_first.collision_free());
  EXPECT_EQ(at_first.contacts.front().body + " " + at_first.contacts.front().other,
            "base_link upper_arm_link");
  vision::RegistrationObservations in_contact = ur6.observations;
  in_contact.configurations = {*first};
  auto refused = capture_start_pose(in_contact, ur6.robot.description, ur6.workspace, ur6.ready);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().message,
            "from none of the 1 observed configurations that show the marker to both cameras is "
            "the straight move to the ready pose free of contact: nowhere to start the capture");
  vision::RegistrationObservations unseen = in_contact;
  unseen.configurations.front().right_pixels.clear();
  auto none = capture_start_pose(unseen, ur6.robot.description, ur6.workspace, ur6.ready);
  ASSERT_FALSE(none.ok());
  EXPECT_THAT(none.error().message,
              HasSubstr("no observed configuration shows the marker to both cameras"));
}

}  // namespace
}  // namespace telear::lab
