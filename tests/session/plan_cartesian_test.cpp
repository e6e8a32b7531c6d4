// Cartesian segments in the session's plan: the `cartesian: true` key of plan files, the
// trajectory the preview plays (the expansion's), the plan message that carries the operator's
// waypoints only and that the server's function times to the same hash, and validation's error
// for a line the arm cannot follow.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "telear/core/inverse_kinematics.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/plan_hash.hpp"
#include "telear/net/plan_message.hpp"
#include "telear/session/plan.hpp"
#include "telear/session/plan_preview.hpp"
#include "telear/session/plan_validation.hpp"
#include "test_util/test_util.hpp"

namespace telear::session {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

using test::q6;

// The IK solution nearest q of q's tool pose moved by `offset` (base frame).
Eigen::VectorXd moved(const core::RobotModel& model, const Eigen::VectorXd& q,
                      const Eigen::Vector3d& offset) {
  Eigen::Isometry3d T = core::tool_pose(model, q);
  T.translation() += offset;
  auto ik = core::solve_ik_nearest(model, T, q);
  EXPECT_TRUE(ik) << ik.error().message;
  return ik ? ik->q : q;
}

// Out along a line of the tool and back along it.
Plan line_plan() {
  Plan plan(test::puma560());
  const Eigen::VectorXd q0 = q6(0, 0.5, -0.5, 0, 0.5, 0);
  PlanWaypoint out(moved(plan.model(), q0, {0.08, 0.05, -0.06}), 0.0, 0.0, "out");
  out.cartesian = true;
  PlanWaypoint back(q0, 0.0, 1.0, "back");
  back.cartesian = true;
  EXPECT_TRUE(plan.add({q0, 0.0, 1.0, "start"}).ok());
  EXPECT_TRUE(plan.add(out).ok());
  EXPECT_TRUE(plan.add(back).ok());
  return plan;
}

TEST(PlanCartesian, PlanFilesCarryTheFlag) {
  const Plan plan = line_plan();
  const std::string yaml = plan.to_yaml();
  EXPECT_THAT(yaml, HasSubstr("cartesian: true"));
  auto loaded = Plan::from_yaml(test::puma560(), yaml, "line.yaml");
  ASSERT_TRUE(loaded) << loaded.error().message;
  ASSERT_EQ(loaded->size(), 3u);
  EXPECT_FALSE(loaded->waypoint(0).cartesian);
  EXPECT_TRUE(loaded->waypoint(1).cartesian);
  EXPECT_TRUE(loaded->joint_waypoints()[2].cartesian);
  auto bad = Plan::from_yaml(test::puma560(),
                             "robot: puma560\nwaypoints:\n  - {q_rad: [0, 0.5, -0.5, 0, 0.5, 0], "
                             "cartesian: yes please}\n",
                             "p.yaml");
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().message, "plan 'p.yaml': waypoint[0].cartesian: must be true or false");
}

TEST(PlanCartesian, TheExampleOfDocsSessionMdIsFollowed) {
  auto plan = Plan::from_yaml(
      test::puma560(),
      "robot: puma560\nvelocity_scale: 0.5\nacceleration_scale: 0.5\nwaypoints:\n"
      "  - {label: approach, q_rad: [0, 0.5, -1.2, 0, 0.7, 0], gripper: 1}\n"
      "  - {label: grasp, q_rad: [0.2, 0.6, -1.1, 0, 0.5, 0], gripper: 0, min_duration_s: 1}\n"
      "  - {label: lift, q_rad: [0.2, 0.4, -1.0, 0, 0.6, 0], cartesian: true}\n",
      "pick.yaml");
  ASSERT_TRUE(plan) << plan.error().message;
  auto trajectory = plan->trajectory();
  ASSERT_TRUE(trajectory) << trajectory.error().message;
  EXPECT_GT(trajectory->waypoints().size(), 3u);  // the lift expanded
}

TEST(PlanCartesian, TheSessionAndTheServerTimeTheSamePlan) {
  const Plan plan = line_plan();
  auto trajectory = plan.trajectory();
  ASSERT_TRUE(trajectory) << trajectory.error().message;
  EXPECT_GT(trajectory->waypoints().size(), 20u);  // the expansion's points
  const std::string previewed = *core::plan_hash(*trajectory);

  // What Session::execute_plan sends, and what the robot server does with it.
  v1::PlanMessage message;
  ASSERT_TRUE(net::fill_plan_message("p-line", *trajectory, message).ok());
  EXPECT_EQ(message.waypoints_size(), 3);
  auto received = net::plan_from_message(plan.model(), message, net::CommandLimits{});
  ASSERT_TRUE(received) << received.error().message;
  EXPECT_EQ(received->hash, previewed);
  EXPECT_EQ(received->trajectory.duration(), trajectory->duration());

  // The preview counts the operator's waypoints, not the expansion's points.
  PlanPreview preview(std::move(*trajectory));
  preview.seek(preview.duration());
  EXPECT_EQ(preview.current().waypoint, 2);
  preview.seek(0.0);
  EXPECT_EQ(preview.current().waypoint, 0);
}

TEST(PlanCartesian, ValidationSaysWhereALineCannotBeFollowed) {
  // To the mirror image of the tool's position through the base axis: the line crosses the
  // axis, where the PUMA's wrist cannot go.
  Plan plan(test::puma560());
  const Eigen::VectorXd q0 = q6(0, 0.5, -0.5, 0, 0.5, 0);
  Eigen::Isometry3d T = core::tool_pose(plan.model(), q0);
  T.translation().head<2>() = -T.translation().head<2>();
  auto far = core::solve_ik_nearest(plan.model(), T, q0);
  ASSERT_TRUE(far) << far.error().message;
  PlanWaypoint line(far->q);
  line.cartesian = true;
  ASSERT_TRUE(plan.add({q0}).ok());
  ASSERT_TRUE(plan.add(line).ok());

  const ValidationReport report = validate_plan(plan, q0);
  ASSERT_EQ(report.error_count(), 1) << report.summary();
  const ValidationIssue& issue = report.issues.front();
  EXPECT_EQ(issue.waypoint, 0);
  EXPECT_THAT(issue.message, StartsWith("waypoint[1]: the Cartesian segment from waypoint[0] "
                                        "cannot be followed at "));
  EXPECT_THAT(issue.message, HasSubstr("the arm cannot reach the line there"));
  // The same joints in joint space are a valid plan.
  line.cartesian = false;
  ASSERT_TRUE(plan.replace(1, line).ok());
  EXPECT_TRUE(validate_plan(plan, q0).ok()) << validate_plan(plan, q0).summary();
}

}  // namespace
}  // namespace telear::session
