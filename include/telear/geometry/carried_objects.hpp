#pragma once
// What a trajectory carries, and the carried object checked for collisions: the one
// implementation behind the session's plan validation (session/plan_collision.hpp) and the
// robot server's collision guard (net/motion_collision_guard.hpp), so that what the operator
// rehearses and what the server accepts agree.
//
// Along the trajectory's waypoints the gripper closes on the workspace's graspable object as
// the grasp model decides (geometry/grasp_model.hpp, the simulator's own: the gap shrinks to
// the object's width while the gripper's centre is within 2 cm of the object's centre); from
// that waypoint until the one where the gripper opens again the object rides in the hand
// (CollisionChecker::attach_object) and is checked against the workspace and the arm. Where it
// is released it drops onto what is under it, as in the simulator, and may be picked again.
//
// The graspable objects are the task's targets, not obstacles: the fingers touch the box at
// the grasp on purpose, so the checker of the static scene is built without them
// (static_obstacles) and only a carried one is checked, by check_carried_objects.

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/core/trajectory.hpp"
#include "telear/core/workspace.hpp"
#include "telear/geometry/collision_checker.hpp"
#include "telear/geometry/robot_collision.hpp"
#include "telear/geometry/trajectory_collision.hpp"

namespace telear::geometry {

// A stretch of a trajectory during which the gripper holds a workspace object.
struct CarriedObject {
  std::string name;         // the workspace object
  std::size_t grasp = 0;    // the waypoint at which the gripper closes on it
  std::size_t release = 0;  // the waypoint at which it opens again (the last when it never does)
  Eigen::Isometry3d T_base_object = Eigen::Isometry3d::Identity();  // where it is picked up
};

// `workspace` without its graspable objects: the scene a checker holds as obstacles.
core::Workspace static_obstacles(const core::Workspace& workspace);

// The stretches of `trajectory`'s waypoints during which the gripper of `robot` holds the
// workspace's graspable object, decided as the grasp model decides (the gripper opening
// initial_gripper_fraction before the first command). None when the workspace has no
// graspable object or the robot no gripper.
std::vector<CarriedObject> carried_objects(const core::Trajectory& trajectory,
                                           const RobotCollisionModel& robot,
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
Result<std::vector<PlanCollision>> check_carried_objects(
    const core::Trajectory& trajectory, const CollisionChecker& checker,
    const core::Workspace& workspace, const TrajectoryCheckOptions& options = {});

// The whole check: `checker` (the static scene: static_obstacles of `workspace`) along the
// trajectory, then the carried objects' contacts (check_carried_objects) merged in, all in
// time order. The clearance stays the static scene's. Errors: either check's own.
Result<TrajectoryCheckReport> check_trajectory_carrying(CollisionChecker& checker,
                                                        const core::Trajectory& trajectory,
                                                        const core::Workspace& workspace,
                                                        const TrajectoryCheckOptions& options = {});

}  // namespace telear::geometry
