#pragma once
// A plan checked for collisions along its whole timed trajectory: the same trajectory the
// preview shows and the robot executes (Plan::trajectory), checked continuously against the
// workspace and the robot itself (geometry/trajectory_collision.hpp), so that no motion
// between two samples steps over an obstacle.

#include "telear/core/result.hpp"
#include "telear/geometry/trajectory_collision.hpp"
#include "telear/session/plan.hpp"

namespace telear::session {

// Errors: the plan cannot be timed (Plan::trajectory), its robot is not the checker's (dof),
// the check's own (options).
Result<geometry::TrajectoryCheckReport> check_plan_collisions(
    const Plan& plan, geometry::CollisionChecker& checker,
    const geometry::TrajectoryCheckOptions& options = {});

}  // namespace telear::session
