#pragma once
// Continuous collision checking of a planned trajectory (core/trajectory.hpp): a motion
// between two samples cannot step over an obstacle, however thin.
//
// Path. Segment k moves every joint on the straight line q(s) = q_k + D s, D = q_{k+1} - q_k,
// s in [0, 1] (the time scaling s(t) only decides when). By robot_collision.hpp's motion
// bound, moving from s to s + ds moves any point of body b at most ds * L_b with
//   L_b = sum_j |D_j| lever(j, b),
// so a pair at distance d cannot touch before ds = d / L: conservative advancement. Body
// against object: L = L_b. Two bodies on frames k_a <= k_b: a common rigid motion keeps their
// distance, and only joints k_a.. move b against a, so L = sum_{j >= k_a} |D_j| lever(j, b). Each
// step advances s by the smallest such ds over the pairs, never below resolution_m / L (a pair
// closer than the resolution may then penetrate by at most resolution_m before it is seen: far
// below a 2 mm plate), and never beyond max_step_m of motion of any body (so that the clearance is
// sampled finely enough: near its minimum the distance is flat, and a step of h misses it by about
// h^2 / 8 rho for a surface of curvature radius rho). A pair's distance is re-computed only once
// its lower bound d_last - (s - s_last) L has fallen below refresh_fraction * d_last, or below the
// smallest clearance found so far (it might set a new minimum), so pairs far apart cost one query
// per segment.
//
// Result: every contact episode (a pair from first contact to separation) with the time the
// contact starts (within resolution_m of motion), the pair and the deepest penetration seen
// while it lasts (sampled every contact_step_m of motion); and the minimum clearance along the
// plan among the distances computed (the true minimum between two computed points lies at
// most the step's motion below them), with its time and pair.
//
// Gripper: the fraction commanded at or before the segment's start (Trajectory::gripper_at),
// initial_gripper_fraction before any command.

#include <limits>
#include <string>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/core/trajectory.hpp"
#include "telear/geometry/collision_checker.hpp"

namespace telear::geometry {

struct PlanCollision {
  double time_s = 0.0;  // when the contact starts, s from the plan's start
  std::string body, other;
  bool self = false;     // `other` is a robot body
  double depth_m = 0.0;  // deepest penetration during the contact
  int segment = 0;       // waypoint k -> k + 1 where it starts
};

struct PlanClearance {
  double distance_m = std::numeric_limits<double>::infinity();
  double time_s = 0.0;
  int segment = 0;
  std::string body, other;
  bool self = false;
};

struct TrajectoryCheckOptions {
  double resolution_m = 1e-4;    // the least step of motion near a surface (> 0)
  double contact_step_m = 1e-3;  // motion between depth samples while in contact (> 0)
  double max_step_m = 0.02;      // the most any body moves in one step (> 0)
  // Mesh pairs are first bounded by a search stopped at this relative error (>= 0; the bound
  // is distance / (1 + relative_error)), and computed exactly only where they might set a new
  // minimum clearance.
  double relative_error = 0.25;
  double refresh_fraction = 0.5;          // (0, 1): re-compute a pair's distance below this share
  double initial_gripper_fraction = 1.0;  // before any gripper command, 0..1
  long max_evaluations = 2'000'000;       // configurations posed, then an error

  Status validate() const;  // names the field
};

struct TrajectoryCheckReport {
  std::vector<PlanCollision> collisions;  // in time order
  PlanClearance min_clearance;            // 0 when in contact
  // The same over the pairs of a body and a workspace object only (the arm's own links can
  // pass close to each other by design: a spherical wrist's housings).
  PlanClearance min_workspace_clearance;
  long evaluations = 0;       // configurations posed
  long distance_queries = 0;  // pair distances computed
  bool collision_free() const { return collisions.empty(); }
};

// Errors: invalid options, a trajectory of another dof, too many evaluations.
Result<TrajectoryCheckReport> check_trajectory(CollisionChecker& checker,
                                               const core::Trajectory& trajectory,
                                               const TrajectoryCheckOptions& options = {});

// The naive baseline: the configuration every dt_s seconds (both ends included), every pair's
// distance, no bounds and no culling. Misses what falls between two samples.
TrajectoryCheckReport check_trajectory_sampled(CollisionChecker& checker,
                                               const core::Trajectory& trajectory, double dt_s,
                                               double initial_gripper_fraction = 1.0);

}  // namespace telear::geometry
