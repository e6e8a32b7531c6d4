#pragma once
// A plan checked for collisions along its whole timed trajectory: the same trajectory the
// preview shows and the robot executes (Plan::trajectory), checked continuously against the
// workspace and the robot itself (geometry/trajectory_collision.hpp), so that no motion
// between two samples steps over an obstacle.
//
// An object the plan carries is checked too (geometry/carried_objects.hpp): along the plan's
// waypoints the gripper closes on the workspace's graspable object as the simulator's grasp
// model decides (geometry/grasp_model.hpp); from that waypoint until the one where the gripper
// opens again the object rides in the hand and is checked against the workspace and the arm.

#include <string>

#include "telear/core/result.hpp"
#include "telear/core/trajectory.hpp"
#include "telear/core/workspace.hpp"
#include "telear/geometry/carried_objects.hpp"
#include "telear/geometry/trajectory_collision.hpp"
#include "telear/session/plan.hpp"

namespace telear::session {

// Errors: the plan cannot be timed (Plan::trajectory), its robot is not the checker's (dof),
// the check's own (options).
Result<geometry::TrajectoryCheckReport> check_plan_collisions(
    const Plan& plan, geometry::CollisionChecker& checker,
    const geometry::TrajectoryCheckOptions& options = {});

// The carried object (geometry/carried_objects.hpp): the one implementation the robot
// server's collision guard shares, so that what validation accepts the server accepts too.
using geometry::carried_objects;
using geometry::CarriedObject;
using geometry::check_carried_objects;
using geometry::kRestingContactDepthM;

// One line for the operator: the first contact ("first contact at t = 1.23 s: link6 hits
// table_top (12.0 mm deep)") or the clearance to the workspace ("collision-free, clearance
// 42 mm (link3 – table_top) at t = 0.80 s").
std::string collision_summary(const geometry::TrajectoryCheckReport& report);

}  // namespace telear::session
