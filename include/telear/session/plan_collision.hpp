#pragma once
// A plan checked for collisions along its whole timed trajectory: the same trajectory the
// preview shows and the robot executes (Plan::trajectory), checked continuously against the
// workspace and the robot itself (geometry/trajectory_collision.hpp), so that no motion
// between two samples steps over an obstacle.

#include <string>

#include "telear/core/result.hpp"
#include "telear/geometry/trajectory_collision.hpp"
#include "telear/session/plan.hpp"

namespace telear::session {

// Errors: the plan cannot be timed (Plan::trajectory), its robot is not the checker's (dof),
// the check's own (options).
Result<geometry::TrajectoryCheckReport> check_plan_collisions(
    const Plan& plan, geometry::CollisionChecker& checker,
    const geometry::TrajectoryCheckOptions& options = {});

// One line for the operator: the first contact ("first contact at t = 1.23 s: link6 hits
// table_top (12.0 mm deep)") or the clearance to the workspace ("collision-free, clearance
// 42 mm (link3 – table_top) at t = 0.80 s").
std::string collision_summary(const geometry::TrajectoryCheckReport& report);

}  // namespace telear::session
