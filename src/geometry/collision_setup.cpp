#include "telear/geometry/collision_checker.hpp"

namespace telear::geometry {

Result<CollisionChecker> make_collision_checker(const core::RobotDescription& description,
                                                const core::Workspace& workspace,
                                                const CollisionSetupOptions& options) {
  Result<RobotCollisionModel> robot = robot_collision_model(description, options.geometry);
  if (!robot) return robot.error();
  Result<AllowedCollisionMatrix> allowed = AllowedCollisionMatrix{};
  if (description.allowed_collisions) {
    // Stored in the robot file: taken as written, adjacent pairs always added.
    allowed = adjacent_collisions(*robot);
    for (const core::AllowedCollisionEntry& e : *description.allowed_collisions) {
      allowed->allow(e.a, e.b, allowed_reason_from_string(e.reason).value_or(AllowedReason::kUser));
    }
  } else {
    allowed = compute_allowed_collisions(*robot, options.allowed);
    if (!allowed) return allowed.error();
  }
  return CollisionChecker::create(std::move(*robot), workspace, std::move(*allowed));
}

}  // namespace telear::geometry
