#include "telear/geometry/collision_checker.hpp"

#include "telear/geometry/allowed_collisions_file.hpp"
#include "telear/geometry/convex_hull.hpp"

namespace telear::geometry {

Result<CollisionChecker> make_collision_checker(const core::RobotDescription& description,
                                                const core::Workspace& workspace,
                                                const CollisionSetupOptions& options) {
  Result<RobotCollisionModel> robot = robot_collision_model(description, options.geometry);
  if (!robot) return robot.error();
  if (options.mesh_collision == MeshCollision::kConvexParts) {
    if (Status s = use_convex_parts(*robot); !s) return s.error();
  }
  Result<AllowedCollisionMatrix> allowed = AllowedCollisionMatrix{};
  if (description.allowed_collisions) {
    // Stored in the robot file: taken as written, adjacent pairs always added.
    allowed = stored_allowed_collisions(*robot, *description.allowed_collisions);
  } else {
    allowed = compute_allowed_collisions(*robot, options.allowed);
    if (!allowed) return allowed.error();
  }
  // The matrix is by link name: found on whole links, it holds for their parts.
  if (options.mesh_collision == MeshCollision::kConvexParts) split_into_parts(*robot);
  return CollisionChecker::create(std::move(*robot), workspace, std::move(*allowed));
}

}  // namespace telear::geometry
