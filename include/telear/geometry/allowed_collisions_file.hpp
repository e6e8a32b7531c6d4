#pragma once
// The allowed-collision matrix as a robot file stores it (docs/robot-files.md,
// docs/collision.md): found once by sampling, as MoveIt's setup assistant does, and written
// under `allowed_collisions:` so that loading the robot takes it as written instead of
// sampling again. `telear robot acm` prints this block; scripts/generate_arms.py writes the
// shipped arms' blocks (tests/geometry checks that they are what sampling finds).
//
//   # The allowed-collision matrix of ur6, found by `telear robot acm` (docs/collision.md):
//   # 2000 random configurations within the joint limits (seed 13), gripper at 0.5,
//   #   constant-distance pairs (within 0.1 mm) allowed.  [one line in the file]
//   allowed_collisions:
//     - [base_link, shoulder_link, adjacent]
//     - [forearm_link, upper_arm_link, adjacent]

#include <string>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/geometry/allowed_collisions.hpp"
#include "telear/geometry/collision_checker.hpp"

namespace telear::geometry {

// The matrix a robot file's entries stand for: the adjacent pairs of `robot`, then the entries
// as written (an entry's reason that is not one of the four reads as user).
AllowedCollisionMatrix stored_allowed_collisions(
    const RobotCollisionModel& robot, const std::vector<core::AllowedCollisionEntry>& entries);

// Samples the matrix of `description` afresh (its stored `allowed_collisions:`, if any, is not
// consulted): the robot's collision bodies (options.geometry), then
// compute_allowed_collisions(options.allowed).
Result<AllowedCollisionMatrix> sample_allowed_collisions(const core::RobotDescription& description,
                                                         const CollisionSetupOptions& options = {});

// The block above for `robot_name`: two comment lines saying how it was found (`options`), the
// key, then one `  - [a, b, reason]` line per pair (`allowed_collisions: []` when there is
// none). Appended to a robot file it loads back to the same matrix.
std::string allowed_collisions_block(const AllowedCollisionMatrix& matrix,
                                     const std::string& robot_name,
                                     const AllowedCollisionOptions& options);

}  // namespace telear::geometry
