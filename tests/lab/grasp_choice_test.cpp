// The grasp choice (include/telear/lab/grasp_choice.hpp) on the PUMA 560 and the simulated
// rig's box: every task position is reachable within the limits with the chosen rotation, the
// marker side faces the cameras better than the naive straight-down grasp, and a box out of
// reach is an error that names it.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "telear/core/angles.hpp"
#include "telear/core/arm_body.hpp"
#include "telear/core/inverse_kinematics.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/robot_loader.hpp"
#include "telear/core/workspace.hpp"
#include "telear/geometry/robot_assets.hpp"
#include "telear/geometry/workspace_meshes.hpp"
#include "telear/lab/demo_task.hpp"
#include "telear/lab/grasp_choice.hpp"
#include "telear/session/plan_collision.hpp"
#include "telear/session/session.hpp"
#include "telear/sim/stereo_rig.hpp"
#include "test_util/test_util.hpp"

namespace telear::lab {
namespace {

struct Fixture {
  core::RobotModelPtr model;
  GraspRequest request;
};

Fixture make_fixture(const Eigen::Vector3d& box) {
  auto model = core::load_robot("puma560");
  EXPECT_TRUE(model.ok());
  auto body = core::body_description_for(**model);
  EXPECT_TRUE(body.ok());
  const core::ArmBody arm_body = core::build_arm_body(*body);
  auto rig = sim::load_stereo_rig(test::data_path("rigs/puma560_rig.yaml"));
  EXPECT_TRUE(rig.ok()) << (rig ? "" : rig.error().message);
  Fixture f{*model, {}};
  for (const TaskStep& s : pick_and_place_steps(box, box + Eigen::Vector3d(0.0, -0.2, 0.0)))
    f.request.grip_positions_base_m.push_back(s.grip_position_base_m);
  f.request.grip_in_link_m = arm_body.gripper
                                 ? Eigen::Vector3d(arm_body.gripper->centre.cast<double>())
                                 : Eigen::Vector3d::Zero();
  Eigen::VectorXd ready_deg(6);  // the demo's start (src/session/demo_workflow.cpp)
  ready_deg << -90.0, 30.0, -120.0, 0.0, -45.0, 0.0;
  f.request.q_start = ready_deg.unaryExpr([](double d) { return core::radians_from_degrees(d); });
  f.request.camera_base_m = rig->cameras.left.T_cam_base.inverse().translation();
  return f;
}

// The box to pick of the PUMA's shipped workspace (data/workspaces/puma560_table.yaml).
Eigen::Vector3d shipped_box_centre() {
  auto workspace = core::load_workspace_file(core::default_workspace_file("puma560"));
  EXPECT_TRUE(workspace.ok()) << workspace.error().message;
  if (!workspace.ok() || !workspace->first_graspable()) return Eigen::Vector3d::Zero();
  return workspace->first_graspable()->T_base_object.translation();
}

double marker_away_deg(const Eigen::Matrix3d& R, const GraspRequest& request) {
  const Eigen::Vector3d to_camera =
      (request.camera_base_m - request.grip_positions_base_m.front()).normalized();
  return core::degrees_from_radians(std::acos(std::clamp(R.col(0).dot(to_camera), -1.0, 1.0)));
}

TEST(GraspChoice, EveryTaskPositionOfTheBoxHasAnInLimitIkSolution) {
  const Fixture f = make_fixture(shipped_box_centre());
  auto choice = choose_grasp(*f.model, f.request);
  ASSERT_TRUE(choice.ok()) << choice.error().message;
  EXPECT_NEAR(
      (choice->R_base_link.transpose() * choice->R_base_link - Eigen::Matrix3d::Identity()).norm(),
      0.0, 1e-12);
  Eigen::VectorXd q = f.request.q_start;
  for (const Eigen::Vector3d& p : f.request.grip_positions_base_m) {
    const Eigen::Isometry3d T = choice->T_base_tool(*f.model, f.request.grip_in_link_m, p);
    auto solution = core::solve_ik_nearest(*f.model, T, q);
    ASSERT_TRUE(solution.ok()) << solution.error().message;
    EXPECT_TRUE(solution->within_limits);
    // Forward kinematics of the solution puts the gripper's centre on the task position.
    const Eigen::Isometry3d T_base_link =
        core::tool_pose(*f.model, solution->q) * f.model->T_flange_tool().inverse();
    EXPECT_LT((T_base_link * f.request.grip_in_link_m - p).norm(), 1e-6);
    EXPECT_LT((T_base_link.linear() - choice->R_base_link).norm(), 1e-6);
    q = solution->q;
  }
  EXPECT_GE(choice->tilt_deg, 0);
  EXPECT_LE(choice->tilt_deg, 60);
  EXPECT_THAT(choice->note(), ::testing::HasSubstr("deg away from facing the cameras"));
}

TEST(GraspChoice, TheMarkerFacesTheCamerasBetterThanStraightDown) {
  const Fixture f = make_fixture(shipped_box_centre());
  auto choice = choose_grasp(*f.model, f.request);
  ASSERT_TRUE(choice.ok()) << choice.error().message;
  Eigen::Matrix3d naive;  // fingers down, no spin: the marker side along +x of the base
  naive.col(0) = Eigen::Vector3d::UnitX();
  naive.col(1) = -Eigen::Vector3d::UnitY();
  naive.col(2) = -Eigen::Vector3d::UnitZ();
  const double chosen = marker_away_deg(choice->R_base_link, f.request);
  EXPECT_LT(chosen, marker_away_deg(naive, f.request));
  EXPECT_NEAR(chosen, choice->away_deg, 0.5);
}

TEST(GraspChoice, AnUnreachableBoxIsAnErrorNamingIt) {
  Fixture f = make_fixture(Eigen::Vector3d(3.0, 0.0, 0.5));
  f.request.object_name = "the far box";
  auto choice = choose_grasp(*f.model, f.request);
  ASSERT_FALSE(choice.ok());
  EXPECT_THAT(choice.error().message,
              ::testing::HasSubstr("no gripper orientation reaches the far box at [3.000, 0.000"));
  EXPECT_THAT(choice.error().message, ::testing::HasSubstr("within the joint limits"));

  f.request.grip_positions_base_m.clear();
  auto empty = choose_grasp(*f.model, f.request);
  ASSERT_FALSE(empty.ok());
  EXPECT_THAT(empty.error().message, ::testing::HasSubstr("no task positions"));
}

// What `telear demo` rehearses and executes on the PUMA (its default robot), offline on a
// collision-checking session: from the demo's start pose the chosen grasp reaches every task
// position elbow-up (the only branch that clears the table and the pedestal within the shipped
// elbow range, data/workspaces/puma560_table.yaml), and the plan, the carried box included, is
// collision-free with the arm at least 5 mm from the workspace.
std::unique_ptr<session::Session> collision_checking_puma_session() {
  auto robot = geometry::load_robot_assets({"puma560", {}, {}});
  EXPECT_TRUE(robot) << robot.error().message;
  auto workspace = geometry::load_workspace(core::default_workspace_file("puma560"));
  EXPECT_TRUE(workspace) << workspace.error().message;
  if (!robot || !workspace) return nullptr;
  session::SessionOptions options;
  options.robot.address = "127.0.0.1:1";  // never connected
  options.vision.address = "127.0.0.1:1";
  options.description = robot->description;
  options.workspace = *workspace;
  auto session = session::Session::create(robot->model(), options);
  EXPECT_TRUE(session) << session.error().message;
  return session ? std::move(*session) : nullptr;
}

TEST(GraspChoice, ThePumasRehearsedPickAndPlaceIsElbowUpAndCollisionFree) {
  auto session = collision_checking_puma_session();
  ASSERT_TRUE(session);
  const Fixture f = make_fixture(shipped_box_centre());
  ASSERT_TRUE(session->move_ghost(core::JointTarget{f.request.q_start}).accepted);
  DemoTaskInputs inputs;
  inputs.box_base_m = shipped_box_centre();
  inputs.grip_in_link_m = f.request.grip_in_link_m;
  inputs.camera_base_m = f.request.camera_base_m;
  auto grasp = choose_task_grasp(*session, inputs);
  ASSERT_TRUE(grasp) << grasp.error().message;
  (void)session->plan().set_scales(0.5, 0.5);
  const Status rehearsed = rehearse_pick_and_place(*session, inputs, *grasp);
  ASSERT_TRUE(rehearsed) << rehearsed.error().message;
  for (const session::PlanWaypoint& w : session->plan().waypoints()) {
    // Elbow-up: the forearm bends down from the elbow (q3 < -90 deg), within the -135 limit.
    EXPECT_LT(core::degrees_from_radians(w.q[2]), -90.0) << w.label;
  }
  const session::ValidationReport report = session->validate_plan();
  EXPECT_TRUE(report.ok()) << report.summary();
  ASSERT_TRUE(report.collision.has_value());
  EXPECT_TRUE(report.collision->collision_free()) << session::collision_summary(*report.collision);
  EXPECT_GT(report.collision->min_workspace_clearance.distance_m, 0.005)
      << session::collision_summary(*report.collision);
}

// Where the box stood before (0.65 m out, on the same table) the PUMA's elbow range reaches it
// only elbow-down, through the table and against its pedestal: on a collision-checking
// session no orientation is chosen, and the error names the first contact and where.
TEST(GraspChoice, OnACollisionCheckingSessionABoxReachedOnlyThroughTheTableIsRefused) {
  auto session = collision_checking_puma_session();
  ASSERT_TRUE(session);
  const Eigen::Vector3d near_box(0.55, -0.35, 0.425);
  const Fixture f = make_fixture(near_box);
  // Without the scene an orientation reaches it (elbow-down).
  ASSERT_TRUE(choose_grasp(*f.model, f.request).ok());
  ASSERT_TRUE(session->move_ghost(core::JointTarget{f.request.q_start}).accepted);
  DemoTaskInputs inputs;
  inputs.box_base_m = near_box;
  inputs.grip_in_link_m = f.request.grip_in_link_m;
  inputs.camera_base_m = f.request.camera_base_m;
  auto grasp = choose_task_grasp(*session, inputs);
  ASSERT_FALSE(grasp.ok());
  // The first task position is the approach, 0.12 m above the box; the least tilted
  // orientation that reaches every position has its forearm through the table top.
  const std::string& message = grasp.error().message;
  EXPECT_THAT(message, ::testing::HasSubstr("every gripper orientation that reaches the box at "
                                            "[0.550, -0.350, 0.545] m (base frame) within the "
                                            "joint limits touches the scene on the way (tilted "));
  EXPECT_THAT(message, ::testing::HasSubstr("link3 and table_top ("));
  EXPECT_THAT(message, ::testing::HasSubstr(" mm deep)); move it where the arm reaches it"));
}

}  // namespace
}  // namespace telear::lab
