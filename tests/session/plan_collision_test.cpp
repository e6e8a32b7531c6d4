// Plans checked for collisions (session/plan_collision.hpp) and plan validation with a
// collision checker (plan_validation.hpp): a contact is an error saying where, a pass closer
// than the safety margin a warning, a clear plan passes.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "telear/geometry/collision_checker.hpp"
#include "telear/geometry/workspace_meshes.hpp"
#include "telear/session/plan_collision.hpp"
#include "telear/session/plan_validation.hpp"
#include "test_util/test_util.hpp"

namespace telear::session {
namespace {

using ::testing::HasSubstr;

using test::q6;

struct Scene {
  core::RobotDescription description;
  geometry::CollisionChecker checker;

  static Scene puma_at_the_table() {
    auto d = core::load_robot_description({"puma560", "", {}});
    EXPECT_TRUE(d) << d.error().message;
    auto w = geometry::load_workspace(core::default_workspace_file("puma560"));
    EXPECT_TRUE(w) << w.error().message;
    auto c = geometry::make_collision_checker(*d, *w);
    EXPECT_TRUE(c) << c.error().message;
    return Scene{std::move(*d), std::move(*c)};
  }
};

TEST(PlanCollision, APlanIntoTheTableFailsValidationSayingWhere) {
  Scene scene = Scene::puma_at_the_table();
  Plan plan(scene.description.model);
  ASSERT_TRUE(plan.add({q6(0, 0, 0, 0, 0, 0)}).ok());
  ASSERT_TRUE(plan.add({q6(0.077, -0.392, -2.334, 0.240, 0.745, 1.557)}).ok());
  auto report = check_plan_collisions(plan, scene.checker);
  ASSERT_TRUE(report) << report.error().message;
  ASSERT_FALSE(report->collision_free());

  ValidationOptions options;
  options.collision_checker = &scene.checker;
  const ValidationReport validation = validate_plan(plan, plan.waypoint(0).q, options);
  ASSERT_FALSE(validation.ok());
  bool table = false;
  for (const ValidationIssue& issue : validation.issues) {
    if (issue.severity != IssueSeverity::kError) continue;
    EXPECT_EQ(issue.waypoint, 0);
    EXPECT_THAT(issue.message,
                HasSubstr("the segment waypoint[0] -> waypoint[1] collides at t = "));
    table = table || issue.message.find("hits table_top (penetration ") != std::string::npos;
  }
  EXPECT_TRUE(table) << validation.summary();
  // Without a checker the same plan is valid (the check is opt-in).
  EXPECT_TRUE(validate_plan(plan, plan.waypoint(0).q).ok());
}

TEST(PlanCollision, PassingWithinTheSafetyMarginWarnsAndAClearPlanPasses) {
  Scene scene = Scene::puma_at_the_table();
  Plan plan(scene.description.model);
  ASSERT_TRUE(plan.add({q6(0, 0, 0, 0, 0, 0)}).ok());
  ASSERT_TRUE(plan.add({q6(0, 1.5707963, -1.5707963, 0, 0, 0)}).ok());
  auto report = check_plan_collisions(plan, scene.checker);
  ASSERT_TRUE(report) << report.error().message;
  ASSERT_TRUE(report->collision_free());
  const double clearance = report->min_workspace_clearance.distance_m;
  ASSERT_GT(clearance, 0.0);

  // (The zero and ready poses are singular: those warnings are not the subject here.)
  const auto margin_warnings = [](const ValidationReport& r) {
    std::vector<std::string> out;
    for (const ValidationIssue& issue : r.issues) {
      if (issue.message.find("safety margin") != std::string::npos) out.push_back(issue.message);
    }
    return out;
  };
  ValidationOptions options;
  options.collision_checker = &scene.checker;
  options.safety_margin_m = clearance - 0.01;
  ValidationReport validation = validate_plan(plan, plan.waypoint(0).q, options);
  EXPECT_TRUE(validation.ok()) << validation.summary();
  EXPECT_TRUE(margin_warnings(validation).empty()) << validation.summary();

  options.safety_margin_m = clearance + 0.01;
  validation = validate_plan(plan, plan.waypoint(0).q, options);
  EXPECT_TRUE(validation.ok());
  const std::vector<std::string> warnings = margin_warnings(validation);
  ASSERT_EQ(warnings.size(), 1u) << validation.summary();
  EXPECT_THAT(warnings[0], HasSubstr("the segment waypoint[0] -> waypoint[1] passes "));
  EXPECT_THAT(warnings[0], HasSubstr("mm from " + report->min_workspace_clearance.other));
  EXPECT_THAT(warnings[0], HasSubstr("within the safety margin of "));

  options.safety_margin_m = -1.0;
  validation = validate_plan(plan, plan.waypoint(0).q, options);
  ASSERT_FALSE(validation.ok());
  EXPECT_THAT(validation.summary(), HasSubstr("safety_margin_m must be a finite number >= 0"));
}

}  // namespace
}  // namespace telear::session
