// Collision checking in the operator's workflow: the ghost's live clearance
// (session/ghost_clearance.hpp) and a Session built with the robot's description and its
// workspace (validate_plan checks the plan, the ghost's clearance follows it, the links in
// contact are handed to the view). The Session is not connected: nothing here needs a server.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "telear/geometry/collision_checker.hpp"
#include "telear/geometry/workspace_meshes.hpp"
#include "telear/session/ghost_clearance.hpp"
#include "telear/session/session.hpp"
#include "telear/session/view_input.hpp"

namespace telear::session {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

Eigen::VectorXd q6(double a, double b, double c, double d, double e, double f) {
  Eigen::VectorXd q(6);
  q << a, b, c, d, e, f;
  return q;
}

// From the zero pose down into the PUMA's table top (plan_collision_test.cpp).
const Eigen::VectorXd kZero = q6(0, 0, 0, 0, 0, 0);
const Eigen::VectorXd kIntoTable = q6(0.077, -0.392, -2.334, 0.240, 0.745, 1.557);

core::RobotDescription puma() {
  auto d = core::load_robot_description({"puma560", "", {}});
  EXPECT_TRUE(d) << d.error().message;
  return std::move(*d);
}

core::Workspace table() {
  auto w = geometry::load_workspace(core::default_workspace_file("puma560"));
  EXPECT_TRUE(w) << w.error().message;
  return std::move(*w);
}

std::unique_ptr<Session> offline_session(double margin = 0.03) {
  SessionOptions options;
  options.robot.address = "127.0.0.1:1";  // never connected
  options.vision.address = "127.0.0.1:1";
  options.description = puma();
  options.workspace = table();
  options.safety_margin_m = margin;
  auto session = Session::create(options.description->model, options);
  EXPECT_TRUE(session) << session.error().message;
  return std::move(*session);
}

// The first configuration along zero -> into the table that is in contact, and the clearance
// of the ones before it.
TEST(GhostClearance, ShrinksAsTheGhostIsMovedTowardsTheTableAndTurnsToContact) {
  auto checker = geometry::make_collision_checker(puma(), table());
  ASSERT_TRUE(checker) << checker.error().message;
  GhostClearance clearance(*checker, 0.03);
  EXPECT_EQ(clearance.state().level, ClearanceState::Level::kUnchecked);

  const ClearanceState far = clearance.update(kZero, 1.0);
  ASSERT_EQ(far.level, ClearanceState::Level::kClear) << far.summary();
  EXPECT_GT(far.workspace.distance_m, 0.03);
  EXPECT_FALSE(far.workspace.self);
  EXPECT_THAT(far.summary(), HasSubstr("clearance "));
  EXPECT_THAT(far.summary(), HasSubstr("mm: " + far.workspace.body));

  double last = far.workspace.distance_m;
  bool within_margin_seen = false, contact_seen = false;
  for (int k = 1; k <= 100 && !contact_seen; ++k) {
    const Eigen::VectorXd q = kZero + (kIntoTable - kZero) * (k / 100.0);
    const ClearanceState& s = clearance.update(q, 1.0);
    if (s.level == ClearanceState::Level::kContact) {
      contact_seen = true;
      ASSERT_FALSE(s.contacts.empty());
      EXPECT_EQ(s.contacts.front().other, "table_top");
      EXPECT_FALSE(s.contact_frames.empty());
      EXPECT_THAT(s.summary(), HasSubstr("contact: "));
      EXPECT_THAT(s.summary(), HasSubstr("table_top"));
    } else {
      if (s.level == ClearanceState::Level::kWithinMargin) {
        within_margin_seen = true;
        EXPECT_LT(s.workspace.distance_m, 0.03);
      }
      last = s.workspace.distance_m;
    }
  }
  EXPECT_TRUE(contact_seen);
  EXPECT_TRUE(within_margin_seen) << "the margin warns before the contact";
  EXPECT_LT(last, far.workspace.distance_m);
}

TEST(SessionCollision, TheGhostsClearanceFollowsItsJogsAndNamesTheLinksInContact) {
  auto session = offline_session();
  ASSERT_TRUE(session->checks_collisions());
  ASSERT_TRUE(session->move_ghost(core::JointTarget{kZero}).accepted);
  const double far = session->ghost_clearance().workspace.distance_m;
  ASSERT_EQ(session->ghost_clearance().level, ClearanceState::Level::kClear);
  EXPECT_TRUE(session->view().ghost_contact_frames.empty());

  ASSERT_TRUE(session->move_ghost(core::JointTarget{kZero + (kIntoTable - kZero) * 0.5}).accepted);
  EXPECT_NE(session->ghost_clearance().workspace.distance_m, far);

  ASSERT_TRUE(session->move_ghost(core::JointTarget{kIntoTable}).accepted);
  EXPECT_EQ(session->ghost_clearance().level, ClearanceState::Level::kContact);
  EXPECT_EQ(session->view().ghost_contact_frames, session->ghost_clearance().contact_frames);
  EXPECT_FALSE(session->view().ghost_contact_frames.empty());
  // The AR view draws those links red.
  EXPECT_EQ(ar_view_input(session->view()).ghost_highlight_frames,
            session->view().ghost_contact_frames);
}

TEST(SessionCollision, ValidationFailsOnAPlanThroughTheTableSayingWhere) {
  auto session = offline_session();
  ASSERT_TRUE(session->plan().add({kZero}).ok());
  ASSERT_TRUE(session->plan().add({kIntoTable}).ok());
  const ValidationReport report = session->validate_plan();
  EXPECT_FALSE(report.ok());
  ASSERT_TRUE(report.collision.has_value());
  ASSERT_FALSE(report.collision->collision_free());
  const geometry::PlanCollision& first = report.collision->collisions.front();
  EXPECT_EQ(first.other, "table_top");
  EXPECT_GT(first.time_s, 0.0);
  EXPECT_THAT(report.summary(), HasSubstr("collides at t = "));
  EXPECT_THAT(report.summary(), HasSubstr(first.body + " hits table_top"));
}

TEST(SessionCollision, APlanNearTheTableButClearOfItPassesWithAMarginWarning) {
  // The plan of plan_collision_test's margin case: clear of the table by some centimetres.
  const Eigen::VectorXd ready = q6(0, 1.5707963, -1.5707963, 0, 0, 0);
  auto probe = offline_session(0.0);
  ASSERT_TRUE(probe->plan().add({kZero}).ok());
  ASSERT_TRUE(probe->plan().add({ready}).ok());
  const ValidationReport clear = probe->validate_plan();
  ASSERT_TRUE(clear.ok()) << clear.summary();
  ASSERT_TRUE(clear.collision && clear.collision->collision_free());
  const double clearance = clear.collision->min_workspace_clearance.distance_m;
  ASSERT_GT(clearance, 0.0);
  EXPECT_THAT(clear.summary(), Not(HasSubstr("safety margin")));

  auto session = offline_session(clearance + 0.01);
  ASSERT_TRUE(session->plan().add({kZero}).ok());
  ASSERT_TRUE(session->plan().add({ready}).ok());
  const ValidationReport report = session->validate_plan();
  EXPECT_TRUE(report.ok()) << report.summary();
  EXPECT_THAT(report.summary(), HasSubstr("within the safety margin of "));
}

TEST(SessionCollision, WithoutADescriptionAndWorkspaceNothingIsChecked) {
  SessionOptions options;
  options.robot.address = "127.0.0.1:1";
  options.vision.address = "127.0.0.1:1";
  auto session = Session::create(puma().model, options);
  ASSERT_TRUE(session);
  EXPECT_FALSE((*session)->checks_collisions());
  EXPECT_EQ((*session)->ghost_clearance().level, ClearanceState::Level::kUnchecked);
  ASSERT_TRUE((*session)->plan().add({kZero}).ok());
  ASSERT_TRUE((*session)->plan().add({kIntoTable}).ok());
  EXPECT_FALSE((*session)->validate_plan().collision.has_value());
}

}  // namespace
}  // namespace telear::session
