#pragma once
// Every inverse-kinematics solution branch of a 6-joint arm, listed and labelled the way
// ik_analytic.hpp lists the PUMA's eight: by a closed form where the arm has one (the PUMA's,
// ik_analytic.hpp; the UR class's, ik_ur.hpp), by a numeric search otherwise.
//
// Closed form (solve_ik_all on such an arm): its existing solutions in label order ("lun",
// "luf", ... "rdf"), a solution repeating an earlier one (every joint within
// `distinct_tolerance_rad` modulo 2 pi: they meet at singularities) dropped, `singular` as the
// closed form flags it; the search options other than distinct_tolerance_rad are unused.
//
// Numeric search (search_ik_branches; solve_ik_all on any other arm). A non-redundant arm
// reaches a generic pose in finitely many configurations (at most 16 for a general 6R chain,
// 8 for the UR and PUMA geometries), modulo 2 pi per revolute joint. They are found by
// `attempts` Levenberg-Marquardt solves (ik_numeric.hpp, no restarts), each from a seed drawn
// uniformly in the joint box by a splitmix64 generator seeded with `seed`: the same call
// gives the same list. So that branches outside the joint limits are listed (and flagged) as
// the PUMA's are, the search runs on a copy of the model whose revolute joints turn freely
// ([-pi, pi], wrapped); prismatic joints keep their limits. Two converged configurations are
// the same branch when every revolute joint differs by at most `distinct_tolerance_rad`
// modulo 2 pi (prismatic joints: by that many metres). The branches are sorted
// lexicographically on their joints wrapped to (-pi, pi] (a stable order that depends only on
// the set found) and labelled "b0", "b1", ...; `singular` when the smallest Jacobian singular
// value is below singular_threshold. This is a search, not a proof: a branch whose basin no
// seed falls into is missed. With the defaults, every one of the 8 branches of generic
// UR-type poses is found (tests/core).
//
// Both: each revolute joint is then moved to its 2 pi equivalent within the limits nearest
// zero where there is one; within_limits when every joint has one.

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

// The branches of `model` (dof <= 6) reaching T_base_tool: the closed form's ("lun", ...)
// where there is one, else search_ik_branches's ("b0", ...). An error when the options are
// invalid, the target is not finite, the arm is redundant (dof > 6: a continuum of
// solutions; use solve_ik_nearest) or the target is unreachable (the closed form says why;
// the search gives its closest miss).
Result<std::vector<IkSolution>> solve_ik_all(const RobotModel& model,
                                             const Eigen::Isometry3d& T_base_tool,
                                             const IkBranchOptions& options = {});

// The numeric search alone, whatever the arm (the reference the closed forms are tested and
// benchmarked against); errors as solve_ik_all's, "none of N seeded attempts converged" when
// unreachable.
Result<std::vector<IkSolution>> search_ik_branches(const RobotModel& model,
                                                   const Eigen::Isometry3d& T_base_tool,
                                                   const IkBranchOptions& options = {});

}  // namespace telear::core
