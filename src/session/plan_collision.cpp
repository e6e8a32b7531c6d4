#include "telear/session/plan_collision.hpp"

#include <algorithm>
#include <cmath>

#include "telear/core/number_format.hpp"

namespace telear::session {

Result<geometry::TrajectoryCheckReport> check_plan_collisions(
    const Plan& plan, geometry::CollisionChecker& checker,
    const geometry::TrajectoryCheckOptions& options) {
  Result<core::Trajectory> trajectory = plan.trajectory();
  if (!trajectory) return trajectory.error();
  return geometry::check_trajectory(checker, *trajectory, options);
}

std::string collision_summary(const geometry::TrajectoryCheckReport& report) {
  using core::format_number;
  if (!report.collision_free()) {
    const geometry::PlanCollision& c = report.collisions.front();
    return "first contact at t = " + format_number(c.time_s, "%.2f") + " s: " + c.body + " hits " +
           (c.self ? "link " : "") + c.other + " (" + format_number(c.depth_m * 1e3, "%.1f") +
           " mm deep)";
  }
  const geometry::PlanClearance& m = report.min_workspace_clearance;
  if (!std::isfinite(m.distance_m)) return "collision-free (no workspace object checked)";
  return "collision-free, clearance " + format_number(m.distance_m * 1e3, "%.0f") + " mm (" +
         m.body + " and " + m.other + ") at t = " + format_number(m.time_s, "%.2f") + " s";
}

}  // namespace telear::session
