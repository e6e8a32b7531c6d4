#include "telear/session/plan_validation.hpp"

#include <gtest/gtest.h>

#include "test_util/test_util.hpp"

namespace telear::session {
namespace {

using test::q6;

Plan good_plan() {
  Plan plan(test::puma560());
  EXPECT_TRUE(plan.add({q6(0, 0.5, -1.2, 0, 0.7, 0)}).ok());
  EXPECT_TRUE(plan.add({q6(0.3, 0.6, -1.0, 0.2, 0.6, 0.1), 0.0}).ok());
  return plan;
}

TEST(PlanValidation, AGoodPlanStartingAtTheRobotPasses) {
  const Plan plan = good_plan();
  const ValidationReport report = validate_plan(plan, plan.waypoint(0).q);
  EXPECT_TRUE(report.ok());
  EXPECT_TRUE(report.issues.empty()) << report.summary();
  EXPECT_EQ(report.summary(), "ok");
}

TEST(PlanValidation, RejectsAPlanStartingFarFromTheRealRobot) {
  const Plan plan = good_plan();
  Eigen::VectorXd real = plan.waypoint(0).q;
  real[1] -= 0.12;  // joint 2
  const ValidationReport report = validate_plan(plan, real);
  ASSERT_FALSE(report.ok());
  ASSERT_EQ(report.error_count(), 1);
  const ValidationIssue& issue = report.issues[0];
  EXPECT_EQ(issue.waypoint, 0);
  EXPECT_EQ(issue.joint, 1);
  EXPECT_EQ(issue.message,
            "the plan starts 0.120 rad (6.9 deg) from the real robot at joint 2 (shoulder; "
            "tolerance 0.010 rad); move the robot to the plan's start or reset the ghost");
  EXPECT_EQ(report.summary(), "1 error:\n  error: " + issue.message);
  // Within a looser tolerance it passes.
  ValidationOptions loose;
  loose.start_tolerance = 0.2;
  EXPECT_TRUE(validate_plan(plan, real, loose).ok());
}

TEST(PlanValidation, EmptyAndUnknownRealState) {
  Plan empty(test::puma560());
  const ValidationReport none = validate_plan(empty, std::nullopt);
  ASSERT_EQ(none.error_count(), 1);
  EXPECT_EQ(none.issues[0].message,
            "the plan is empty; add at least one waypoint (the ghost's pose)");

  const ValidationReport unknown = validate_plan(good_plan(), std::nullopt);
  EXPECT_TRUE(unknown.ok());
  ASSERT_EQ(unknown.warning_count(), 1);
  EXPECT_EQ(unknown.issues[0].message,
            "the real robot's state is unknown: the plan's start was not checked");
  EXPECT_EQ(unknown.summary(),
            "ok, 1 warning:\n  warning: the real robot's state is unknown: the plan's start was "
            "not checked");

  Eigen::VectorXd bad = good_plan().waypoint(0).q;
  bad[3] = std::nan("");
  const ValidationReport invalid = validate_plan(good_plan(), bad);
  ASSERT_EQ(invalid.error_count(), 1);
  EXPECT_EQ(invalid.issues[0].message.rfind("the real robot's reported state is invalid: ", 0), 0u)
      << invalid.issues[0].message;
}

TEST(PlanValidation, WarnsOfSingleWaypointsAndSingularities) {
  Plan single(test::puma560());
  ASSERT_TRUE(single.add({q6(0, 0.5, -1.2, 0, 0.7, 0)}).ok());
  const ValidationReport one = validate_plan(single, single.waypoint(0).q);
  EXPECT_TRUE(one.ok());
  ASSERT_EQ(one.warning_count(), 1);
  EXPECT_EQ(one.issues[0].message, "the plan has a single waypoint: executing it moves nothing");

  // The wrist passes through q5 = 0 (wrist singularity) in the middle of the segment.
  Plan wrist(test::puma560());
  ASSERT_TRUE(wrist.add({q6(0, 0.5, -1.2, 0, 0.2, 0)}).ok());
  ASSERT_TRUE(wrist.add({q6(0, 0.5, -1.2, 0, -0.2, 0)}).ok());
  const ValidationReport report = validate_plan(wrist, wrist.waypoint(0).q);
  EXPECT_TRUE(report.ok());
  ASSERT_EQ(report.warning_count(), 1) << report.summary();
  EXPECT_EQ(report.issues[0].waypoint, 0);
  // The straight path is symmetric about q5 = 0; the samples nearest it are at 47 % and 53 %.
  const std::string& message = report.issues[0].message;
  EXPECT_EQ(message.rfind("the segment waypoint[0] -> waypoint[1] (at ", 0), 0u) << message;
  EXPECT_NE(message.find(" % of it) is near a singularity: smallest Jacobian singular value "
                         "0.00678 (warning below 0.01); check that part of the preview"),
            std::string::npos)
      << message;
}

TEST(PlanValidation, ReportsPlansTheRobotWouldRefuse) {
  // Too many samples for the server at the session's rate: a long dwell at 1 kHz.
  Plan plan = good_plan();
  ASSERT_TRUE(plan.set_min_duration(1, 200.0).ok());
  ValidationOptions options;
  options.sample_rate_hz = 1000.0;
  const ValidationReport report = validate_plan(plan, plan.waypoint(0).q, options);
  ASSERT_FALSE(report.ok());
  EXPECT_EQ(report.issues[0].message.rfind("the plan cannot be sent: ", 0), 0u)
      << report.issues[0].message;
}

}  // namespace
}  // namespace telear::session
