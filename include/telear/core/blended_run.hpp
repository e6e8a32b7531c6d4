#pragma once
// The timing of one run of via waypoints between two stops: linear segments with parabolic
// blends (LSPB, as in Craig's "Introduction to Robotics", ch. 7, with the blend durations of
// Kunz & Stilman's time-optimal paths replaced by a simpler feasible choice). Used by
// Trajectory::create (telear/core/trajectory.hpp, which explains the profile).
//
// Points P_0 .. P_n (n >= 2 segments; P_0 and P_n are stops, P_1 .. P_{n-1} via points), each
// segment moving (some joint's displacement above the stationary threshold). Segment s moves
// at v_s = (P_{s+1} - P_s) / T_s; with v_{-1} = v_n = 0 (rest), the blend at point k lasts
//
//   b_k = max_j |v_kj - v_{k-1}j| / a_j                          (joint j at its max accel)
//
// and the timing is valid when every b_k <= min(T_{k-1}, T_k) (a missing neighbour does not
// count), so the blends inside a segment (half of each end's) never overlap, and every
// |v_sj| <= v_j. Choice of T_s:
//   1. T_s = max(alpha_s, min_duration_s), alpha_s = max_j |D_sj| / v_j: the slowest joint at
//      full speed (the velocity limit holds from here on, since T only grows). For the first
//      and last segments min_duration counts the half blend at the stop too (the time from
//      leaving P_0, or to arriving at P_n): T_0 + b_0 / 2 >= min_duration_0, b_0 = beta_0 / T_0;
//   2. up to kMaxRepairRounds rounds: for each point k whose blend does not fit, lengthen its
//      neighbouring segments by f = sqrt(b_k / min(T_{k-1}, T_k)) (plus 1e-9 so rounding
//      cannot stall it): their velocities, hence b_k, fall by f while the room grows by f;
//   3. if a blend still does not fit, every T_s = max(T_s, sqrt(2 max(beta_{s-1}, beta_s,
//      beta_{s+1}))), beta_s = max_j |D_sj| / a_j, which makes every blend fit whatever the
//      other durations (docs/trajectory.md has the two-line proof);
//   4. each b_k is finally clamped to its room, so a rounding excess of a few ulps shows up as
//      an acceleration a few ulps above the limit, never as overlapping blends.
// Only +, -, *, /, sqrt and comparisons, in a fixed order: deterministic (trajectory.hpp).
//
// Trajectory::create uses a run only when it is not slower than stopping at its via points;
// otherwise it stops at the sharpest corner (sharpest_corner) and tries both halves again.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace telear::core {

struct BlendedRun {
  std::vector<double> segment_durations;    // T_s, n values, s
  std::vector<double> blend_durations;      // b_k, n + 1 values, s (b_0, b_n: from / to rest)
  std::vector<Eigen::VectorXd> velocities;  // v_s, n joint vectors, per s
  int repair_rounds = 0;                    // rounds of step 2 that changed something
  bool used_fallback = false;               // step 3 was needed

  // From leaving P_0 at rest to arriving at P_n at rest: b_0 / 2 + sum T_s + b_n / 2.
  double duration() const;
};

inline constexpr int kMaxRepairRounds = 64;

// `points` holds n + 1 joint vectors, `min_durations` n values (segment s's lower bound on
// T_s); `v_max` and `a_max` the (scaled) joint limits, all positive. Asserts the shapes.
BlendedRun time_blended_run(const std::vector<Eigen::VectorXd>& points,
                            const std::vector<double>& min_durations, const Eigen::VectorXd& v_max,
                            const Eigen::VectorXd& a_max);

// The via point 1..n-1 whose corner needs the most room for its blend relative to the room
// it has when both its segments run at full speed: max_j |v_kj - v_{k-1}j| / a_j over
// min(alpha_{k-1}, alpha_k) with v_s = D_s / alpha_s. The first of equals.
std::size_t sharpest_corner(const std::vector<Eigen::VectorXd>& points,
                            const Eigen::VectorXd& v_max, const Eigen::VectorXd& a_max);

}  // namespace telear::core
