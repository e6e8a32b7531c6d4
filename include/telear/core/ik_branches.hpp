#pragma once
// Every inverse-kinematics solution branch of a 6-joint arm that has no closed form, found
// numerically, listed and labelled the way ik_analytic.hpp lists the PUMA's eight.
//
// A non-redundant arm reaches a generic pose in finitely many configurations (at most 16 for
// a general 6R chain, 8 for the UR and PUMA geometries), modulo 2 pi per revolute joint. They
// are found by `attempts` Levenberg-Marquardt solves (ik_numeric.hpp, no restarts), each from
// a seed drawn uniformly in the joint box by a splitmix64 generator seeded with `seed`: the
// same call gives the same list. So that branches outside the joint limits are listed (and
// flagged) as the PUMA's are, the search runs on a copy of the model whose revolute joints
// turn freely ([-pi, pi], wrapped); prismatic joints keep their limits.
//
// Two converged configurations are the same branch when every revolute joint differs by at
// most `distinct_tolerance_rad` modulo 2 pi (prismatic joints: by that many metres). Each
// branch's joints are wrapped to (-pi, pi], the branches sorted lexicographically on those
// values (a stable order that depends only on the set found), labelled "b0", "b1", ..., and
// then each revolute joint is moved to its 2 pi equivalent within the limits nearest zero
// where there is one. Flags: within_limits (some 2 pi equivalent of every joint within the
// limits) and singular (smallest Jacobian singular value below singular_threshold).
//
// This is a search, not a proof: a branch whose basin no seed falls into is missed. With the
// defaults, every one of the 8 branches of generic UR-type poses is found (tests/core).

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "telear/core/ik_analytic.hpp"
#include "telear/core/result.hpp"
#include "telear/core/robot_model.hpp"

namespace telear::core {

struct IkBranchOptions {
  int attempts = 96;                         // seeded LM solves, each from a fresh seed
  int max_branches = 16;                     // stop early once this many are found
  std::uint64_t seed = 0xb7a9c4e5;           // of the seed generator
  int max_iterations = 100;                  // per LM solve
  double position_tolerance_m = 1e-10;       // a solve converges at |dp| below this ...
  double orientation_tolerance_rad = 1e-10;  // ... and |log dR| below this
  double distinct_tolerance_rad = 1e-4;      // closer than this per joint: one branch
  double singular_threshold = 1e-6;          // smallest Jacobian singular value
};

// OK, or an error naming the field: "IkBranchOptions::attempts must be positive, got 0".
Status check_ik_branch_options(const IkBranchOptions& options);

// The branches of `model` (dof <= 6) reaching T_base_tool, labelled "b0", ...; an error when
// the options are invalid, the target is not finite, the arm is redundant (dof > 6: a
// continuum of solutions; use solve_ik_nearest) or no attempt converged (unreachable, with
// the closest miss in the message).
Result<std::vector<IkSolution>> solve_ik_all(const RobotModel& model,
                                             const Eigen::Isometry3d& T_base_tool,
                                             const IkBranchOptions& options = {});

}  // namespace telear::core
