// Collision checking in the operator's workflow: the ghost's live clearance
// (session/ghost_clearance.hpp) and a Session built with the robot's description and its
// workspace (validate_plan checks the plan, the ghost's clearance follows it, the links in
// contact are handed to the view). The Session is not connected: nothing here needs a server.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "telear/core/angles.hpp"
#include "telear/core/arm_body.hpp"
#include "telear/geometry/collision_checker.hpp"
#include "telear/geometry/robot_assets.hpp"
#include "telear/geometry/workspace_meshes.hpp"
#include "telear/lab/demo_task.hpp"
#include "telear/lab/embedded_servers.hpp"
#include "telear/net/motion_collision_guard.hpp"
#include "telear/net/robot_client.hpp"
#include "telear/session/ghost_clearance.hpp"
#include "telear/session/plan_collision.hpp"
#include "telear/session/session.hpp"
#include "telear/sim/stereo_rig.hpp"
#include "telear/view/ar_view_input.hpp"
#include "test_util/test_util.hpp"

namespace telear::session {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

using test::q6;

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
  EXPECT_EQ(view::ar_view_input(session->view()).ghost_highlight_frames,
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

// The demo's pick-and-place (demo_task.hpp) rehearsed offline on a shipped arm in its
// workspace: the session checks collisions, the box is carried from the grasp to the place.
struct RehearsedTask {
  std::unique_ptr<Session> session;
  lab::DemoTaskInputs inputs;
  lab::GraspChoice grasp;
};

RehearsedTask rehearse_demo_task(const std::string& robot_name) {
  RehearsedTask task;
  auto robot = geometry::load_robot_assets({robot_name, {}, {}});
  EXPECT_TRUE(robot) << robot.error().message;
  auto workspace = geometry::load_workspace(core::default_workspace_file(robot_name));
  EXPECT_TRUE(workspace) << workspace.error().message;
  auto rig = sim::load_stereo_rig(sim::default_rig_file(robot_name));
  EXPECT_TRUE(rig) << rig.error().message;
  if (!robot || !workspace || !rig) return task;
  SessionOptions options;
  options.robot.address = "127.0.0.1:1";  // never connected
  options.vision.address = "127.0.0.1:1";
  options.description = robot->description;
  options.workspace = *workspace;
  auto session = Session::create(robot->model(), options);
  EXPECT_TRUE(session) << session.error().message;
  if (!session) return task;
  task.session = std::move(*session);
  const auto ready = robot->model()->named_configuration("ready");
  EXPECT_TRUE(ready.has_value());
  if (!ready) return task;
  EXPECT_TRUE(task.session->move_ghost(core::JointTarget{*ready}).accepted);
  const core::ArmBody arm_body = core::build_arm_body(robot->body);
  task.inputs.box_base_m = workspace->first_graspable()->T_base_object.translation();
  task.inputs.grip_in_link_m = arm_body.gripper
                                   ? Eigen::Vector3d(arm_body.gripper->centre.cast<double>())
                                   : Eigen::Vector3d::Zero();
  task.inputs.camera_base_m = rig->cameras.left.T_cam_base.inverse().translation();
  auto grasp = lab::choose_task_grasp(*task.session, task.inputs);
  EXPECT_TRUE(grasp) << grasp.error().message;
  if (!grasp) return task;
  task.grasp = *grasp;
  (void)task.session->plan().set_scales(0.5, 0.5);
  const Status rehearsed = lab::rehearse_pick_and_place(*task.session, task.inputs, task.grasp);
  EXPECT_TRUE(rehearsed) << rehearsed.error().message;
  return task;
}

std::size_t waypoint_labelled(const Plan& plan, const std::string& label) {
  for (std::size_t k = 0; k < plan.size(); ++k) {
    if (plan.waypoint(k).label == label) return k;
  }
  ADD_FAILURE() << "no waypoint labelled " << label;
  return 0;
}

// What the demo executes on the shipped URDF arms: no contact along the plan (the box carried
// included); only the fingers come within the margin of the tray, at the grasp and the place.
TEST(DemoTaskCollision, TheRehearsedPickAndPlaceOfTheShippedArmsIsCollisionFree) {
  for (const std::string name : {"ur6", "arm7"}) {
    RehearsedTask task = rehearse_demo_task(name);
    ASSERT_TRUE(task.session && task.session->checks_collisions()) << name;
    const ValidationReport report = task.session->validate_plan();
    EXPECT_TRUE(report.ok()) << name << ": " << report.summary();
    ASSERT_TRUE(report.collision.has_value()) << name;
    EXPECT_TRUE(report.collision->collision_free()) << name;
    EXPECT_GT(report.collision->min_workspace_clearance.distance_m, 0.005) << name;
    EXPECT_THAT(collision_summary(*report.collision), HasSubstr("collision-free, clearance "))
        << name;
  }
}

TEST(CarriedObject, TheBoxIsHeldFromTheGraspToThePlaceAndRestingOnTheTrayIsNoContact) {
  RehearsedTask task = rehearse_demo_task("ur6");
  ASSERT_TRUE(task.session && task.session->checks_collisions());
  const Plan& plan = task.session->plan();
  auto trajectory = plan.trajectory();
  ASSERT_TRUE(trajectory) << trajectory.error().message;
  auto robot = geometry::robot_collision_model(*task.session->options().description);
  ASSERT_TRUE(robot) << robot.error().message;
  const core::Workspace& workspace = *task.session->options().workspace;
  const std::vector<CarriedObject> carried = carried_objects(*trajectory, *robot, workspace);
  ASSERT_EQ(carried.size(), 1u);
  EXPECT_EQ(carried[0].name, "box");
  EXPECT_EQ(carried[0].grasp, waypoint_labelled(plan, "grasp"));
  EXPECT_EQ(carried[0].release, waypoint_labelled(plan, "place"));
  EXPECT_TRUE(carried[0].T_base_object.translation().isApprox(task.inputs.box_base_m));

  // Picked off the tray and put back on it: those resting contacts are not collisions.
  const ValidationReport report = task.session->validate_plan();
  EXPECT_TRUE(report.ok()) << report.summary();
  EXPECT_THAT(report.summary(), Not(HasSubstr("box hits")));
  // The robot server's guard decides the same (the one implementation): it accepts the plan,
  // the fingers closing on the box at the grasp included.
  auto guard = net::MotionCollisionGuard::create(*task.session->options().description, workspace,
                                                 "", net::kDefaultSafetyMarginM);
  ASSERT_TRUE(guard) << guard.error().message;
  const Status accepted = (*guard)->check_trajectory(*trajectory, 1.0);
  EXPECT_TRUE(accepted) << accepted.error().message;

  // Without a graspable object, or with the gripper never closing, nothing is carried.
  core::Workspace bare = workspace;
  std::erase_if(bare.objects, [](const core::WorkspaceObject& o) { return o.graspable; });
  EXPECT_TRUE(carried_objects(*trajectory, *robot, bare).empty());
  Plan open_hand(plan.model_ptr());
  for (PlanWaypoint w : plan.waypoints()) {
    w.gripper = 1.0;
    ASSERT_TRUE(open_hand.add(w).ok());
  }
  auto open_trajectory = open_hand.trajectory();
  ASSERT_TRUE(open_trajectory) << open_trajectory.error().message;
  EXPECT_TRUE(carried_objects(*open_trajectory, *robot, workspace).empty());
}

TEST(CarriedObject, APlanThatCarriesTheBoxThroughTheTrayIsRefusedNamingTheBox) {
  RehearsedTask task = rehearse_demo_task("ur6");
  ASSERT_TRUE(task.session && task.session->checks_collisions());
  Session& session = *task.session;
  // The carry step lowered until the box's bottom is 15 mm inside the tray (its top is at
  // z = 0.02 m; the box hangs 25 mm below the gripper's centre).
  const std::size_t carry = waypoint_labelled(session.plan(), "carry");
  const std::vector<lab::TaskStep> steps = lab::demo_task_steps(task.inputs);
  const auto step = std::find_if(steps.begin(), steps.end(),
                                 [](const lab::TaskStep& s) { return s.label == "carry"; });
  ASSERT_NE(step, steps.end());
  Eigen::Vector3d low = step->grip_position_base_m;
  low.z() = 0.02 + 0.025 - 0.015;
  const core::MotionOutcome moved = session.move_ghost(core::CartesianTarget{
      task.grasp.T_base_tool(session.model(), task.inputs.grip_in_link_m, low)});
  ASSERT_TRUE(moved.accepted) << moved.rejection.message;
  std::vector<PlanWaypoint> waypoints = session.plan().waypoints();
  waypoints[carry].q = session.ghost().q();
  session.plan().clear();
  for (const PlanWaypoint& w : waypoints) ASSERT_TRUE(session.plan().add(w).ok());

  const ValidationReport report = session.validate_plan();
  EXPECT_FALSE(report.ok());
  EXPECT_THAT(report.summary(), HasSubstr("box hits tray (penetration "));
  ASSERT_TRUE(report.collision.has_value());
  const auto box =
      std::find_if(report.collision->collisions.begin(), report.collision->collisions.end(),
                   [](const geometry::PlanCollision& c) { return c.body == "box"; });
  ASSERT_NE(box, report.collision->collisions.end());
  EXPECT_EQ(box->other, "tray");
  EXPECT_FALSE(box->self);
  EXPECT_GT(box->depth_m, 0.005);
  // On the way down to the low carry pose (from the lift, before the place).
  auto trajectory = session.plan().trajectory();
  ASSERT_TRUE(trajectory);
  EXPECT_GT(box->time_s, trajectory->waypoint_times()[carry - 1]);
  EXPECT_LE(box->time_s, trajectory->waypoint_times()[carry]);
  EXPECT_EQ(static_cast<std::size_t>(box->segment), carry - 1);
  // The session refuses to execute it.
  EXPECT_FALSE(session.execute_plan().ok());
  // So does the robot server's guard, naming the carried box.
  auto guard = net::MotionCollisionGuard::create(
      *session.options().description, *session.options().workspace, "", net::kDefaultSafetyMarginM);
  ASSERT_TRUE(guard) << guard.error().message;
  const Status refused = (*guard)->check_trajectory(*trajectory, 1.0);
  ASSERT_FALSE(refused);
  EXPECT_THAT(refused.error().message, HasSubstr("trajectory collides: at t="));
  EXPECT_THAT(refused.error().message, HasSubstr("the carried 'box' touches 'tray' (depth "));
}

// The embedded servers of `telear demo` and `telear console` are the collision authority in
// the robot's shipped workspace, as `telear robot-server --workspace` is.
TEST(EmbeddedServersCollision, ServeRobotMakesTheRobotServerTheAuthorityInTheShippedWorkspace) {
  auto robot = geometry::load_robot_assets({"arm7", {}, {}});
  ASSERT_TRUE(robot) << robot.error().message;
  lab::EmbeddedServersOptions options;
  ASSERT_TRUE(lab::serve_robot(options, robot->description).ok());
  EXPECT_EQ(options.workspace_file, core::default_workspace_file("arm7"));
  ASSERT_TRUE(options.robot_description.has_value());
  EXPECT_EQ(options.robot_description->name, "arm7");

  // A workspace the caller chose is kept.
  lab::EmbeddedServersOptions chosen;
  chosen.workspace_file = core::default_workspace_file("ur6");
  ASSERT_TRUE(lab::serve_robot(chosen, robot->description).ok());
  EXPECT_EQ(chosen.workspace_file, core::default_workspace_file("ur6"));

  // The embedded robot server started with them checks collisions and says so on GetInfo.
  auto servers = lab::EmbeddedServers::create(robot->model(), options);
  ASSERT_TRUE(servers) << servers.error().message;
  net::RobotClientOptions client_options;
  client_options.address = (*servers)->robot_address();
  client_options.token = (*servers)->token();
  net::RobotClient client(client_options);
  auto info = client.get_info();
  ASSERT_TRUE(info) << info.error().message;
  EXPECT_TRUE(info->collision_checked);
  EXPECT_THAT(info->workspace_yaml, HasSubstr("name: arm7_table"));
}

}  // namespace
}  // namespace telear::session
