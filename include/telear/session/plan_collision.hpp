#pragma once
// A plan checked for collisions along its whole timed trajectory: the same trajectory the
// preview shows and the robot executes (Plan::trajectory), checked continuously against the
// workspace and the robot itself (geometry/trajectory_collision.hpp), so that no motion
// between two samples steps over an obstacle.
//
// An object the plan carries is checked too. Along the plan's waypoints the gripper closes
// on the workspace's graspable object as the simulator's grasp model decides
// (sim/grasp_model.hpp: the gap shrinks to the object's width while the gripper's centre is
// within 2 cm of the object's centre); from that waypoint until the one where the gripper
// opens again the object rides in the hand (geometry::CollisionChecker::attach_object) and
// is checked against the workspace and the arm. Where it is released it drops onto what is
// under it, as in the simulator, and may be picked again.

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/core/trajectory.hpp"
#include "telear/core/workspace.hpp"
#include "telear/geometry/trajectory_collision.hpp"
#include "telear/session/plan.hpp"

namespace telear::session {

// Errors: the plan cannot be timed (Plan::trajectory), its robot is not the checker's (dof),
// the check's own (options).
Result<geometry::TrajectoryCheckReport> check_plan_collisions(
    const Plan& plan, geometry::CollisionChecker& checker,
    const geometry::TrajectoryCheckOptions& options = {});

// A stretch of the plan during which the gripper holds a workspace object.
struct CarriedObject {
  std::string name;         // the workspace object
  std::size_t grasp = 0;    // the waypoint at which the gripper closes on it
  std::size_t release = 0;  // the waypoint at which it opens again (the last when it never does)
  Eigen::Isometry3d T_base_object = Eigen::Isometry3d::Identity();  // where it is picked up
};

// The stretches of `trajectory`'s waypoints during which the gripper of `robot` holds the
// workspace's graspable object, decided as the simulator's grasp model decides (the gripper
// opening initial_gripper_fraction before the first command). None when the workspace has no
// graspable object or the robot no gripper.
std::vector<CarriedObject> carried_objects(const core::Trajectory& trajectory,
                                           const geometry::RobotCollisionModel& robot,
                                           const core::Workspace& workspace,
                                           double initial_gripper_fraction = 1.0);

// A held object may touch what it rests on where it is picked up and put down: its contacts
// no deeper than this are not collisions (m).
inline constexpr double kRestingContactDepthM = 1e-3;

// The carried objects' contacts along `trajectory`: for each stretch, `checker`'s robot and
// allowed-collision matrix with the object held (its workspace objects from `workspace`, the
// graspable one where it is picked up) check that stretch; the contacts of the held object
// (body = its name) deeper than kRestingContactDepthM are returned with the times and segments
// of `trajectory`, in time order. Errors: the check's own.
Result<std::vector<geometry::PlanCollision>> check_carried_objects(
    const core::Trajectory& trajectory, const geometry::CollisionChecker& checker,
    const core::Workspace& workspace, const geometry::TrajectoryCheckOptions& options = {});

// One line for the operator: the first contact ("first contact at t = 1.23 s: link6 hits
// table_top (12.0 mm deep)") or the clearance to the workspace ("collision-free, clearance
// 42 mm (link3 – table_top) at t = 0.80 s").
std::string collision_summary(const geometry::TrajectoryCheckReport& report);

}  // namespace telear::session
