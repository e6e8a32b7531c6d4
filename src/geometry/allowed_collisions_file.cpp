#include "telear/geometry/allowed_collisions_file.hpp"

#include <sstream>

#include "telear/core/number_format.hpp"
#include "telear/geometry/convex_hull.hpp"

namespace telear::geometry {

AllowedCollisionMatrix stored_allowed_collisions(
    const RobotCollisionModel& robot, const std::vector<core::AllowedCollisionEntry>& entries) {
  // Adjacent pairs first: a file that leaves them out still never checks a joint's two sides
  // against each other (their shapes meet at the joint by construction).
  AllowedCollisionMatrix m = adjacent_collisions(robot);
  for (const core::AllowedCollisionEntry& e : entries) {
    m.allow(e.a, e.b, allowed_reason_from_string(e.reason).value_or(AllowedReason::kUser));
  }
  return m;
}

Result<AllowedCollisionMatrix> sample_allowed_collisions(const core::RobotDescription& description,
                                                         const CollisionSetupOptions& options) {
  Result<RobotCollisionModel> robot = robot_collision_model(description, options.geometry);
  if (!robot) return robot.error();
  if (options.mesh_collision == MeshCollision::kConvexParts) {
    if (Status s = use_convex_parts(*robot); !s) return s.error();
  }
  return compute_allowed_collisions(*robot, options.allowed);
}

std::string allowed_collisions_block(const AllowedCollisionMatrix& matrix,
                                     const std::string& robot_name,
                                     const AllowedCollisionOptions& options) {
  std::ostringstream out;
  out << "# The allowed-collision matrix of " << robot_name
      << ", found by `telear robot acm` (docs/collision.md):\n"
      << "# " << options.samples << " random configurations within the joint limits (seed "
      << options.seed << "), gripper at " << core::format_number(options.gripper_fraction);
  if (options.allow_constant) {
    out << ", constant-distance pairs (within "
        << core::format_number(options.constant_tolerance_m * 1e3) << " mm) allowed";
  }
  out << (options.allow_never ? ", never-in-contact pairs allowed" : "") << ".\n";
  if (matrix.pairs().empty()) {
    out << "allowed_collisions: []\n";
    return out.str();
  }
  out << "allowed_collisions:\n";
  std::istringstream lines(matrix.to_yaml());
  for (std::string line; std::getline(lines, line);) out << "  " << line << "\n";
  return out.str();
}

}  // namespace telear::geometry
