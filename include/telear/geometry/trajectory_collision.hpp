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
// distance, and only joints k_a.. move b against a, so L = sum_{j >= k_a} |D_j| lever(j, b).
//
// Per-pair advancement: each pair keeps its own next look. After a look at s that found d (a
// lower bound) the pair is due again at s + ds / L, ds the larger of
//   - d minus the larger of refresh_fraction * d and the smallest clearance so far (below
//     either the pair must be looked at again: it might set a new minimum), and
//   - min(max(d, resolution_m), max_step_m): conservative advancement, which cannot pass a
//     contact by more than resolution_m of penetration (far below a 2 mm plate), and samples a
//     pair that might set the minimum clearance every max_step_m of motion (near its minimum
//     the distance is flat; a vertex passing a face is sampled within max_step_m / 2).
// Only the pairs due are looked at (their bodies posed; with them any pair that has used 80 %
// of its interval, so that one configuration serves several pairs), so a pair a few millimetres
// apart by design (a spherical wrist's housings) is looked at often without shortening anyone
// else's step. A look first takes the distance of the two sides' axis-aligned bounds (no FCL
// query): kept as the pair's bound while it is above the smallest clearance so far and above
// refresh_fraction of the pair's last computed distance. Bounds carry over from one segment to
// the next (less the motion since their look), except across a gripper change.
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
  // The most a pair that might set a new minimum clearance moves between two looks (> 0): a
  // vertex passing a face is then sampled within max_step_m / 2 of its closest approach.
  double max_step_m = 0.005;
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
