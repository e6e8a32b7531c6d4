#include "telear/session/plan_collision.hpp"

namespace telear::session {

Result<geometry::TrajectoryCheckReport> check_plan_collisions(
    const Plan& plan, geometry::CollisionChecker& checker,
    const geometry::TrajectoryCheckOptions& options) {
  Result<core::Trajectory> trajectory = plan.trajectory();
  if (!trajectory) return trajectory.error();
  return geometry::check_trajectory(checker, *trajectory, options);
}

}  // namespace telear::session
