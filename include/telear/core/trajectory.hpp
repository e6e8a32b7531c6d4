#pragma once
// Joint waypoints -> a time-parameterized trajectory within each joint's velocity and
// acceleration limits, its sampled form (what crosses the network as one message), and the
// validation of both when they come from an untrusted sender. This is the one time
// parameterization of telear: the session's preview and the robot server's ExecutePlan both
// call Trajectory::create, and plan_hash (telear/core/plan_hash.hpp) fingerprints the result.
// Method, guarantees and figures: docs/trajectory.md.
//
// Stop waypoints (the default). The arm stops at a waypoint unless it is marked `via`.
// Between two stop waypoints k and k+1 all joints share one trapezoidal time scaling s(t) in
// [0, 1] (telear/core/trapezoidal_profile.hpp):
//
//   q(t) = q_k + (q_{k+1} - q_k) s(t - t_k)
//
// so every joint starts and finishes the segment together and the path is the straight line
// in joint space whatever the speed (the preview, the singularity check and the real arm all
// follow the same path). The joint that needs longest, at its own max velocity or max
// acceleration, sets the segment's duration; the others move proportionally slower. A
// waypoint's min_duration stretches its segment (lower cruise speed, same ramps).
//
// Via waypoints (blends). A run of via waypoints between two stops is timed as linear
// segments with parabolic blends (LSPB): segment s moves at the constant joint velocity
// v_s = D_s / T_s (D_s its displacement, T_s its nominal duration), and around each via
// waypoint k the velocity changes linearly from v_{k-1} to v_k over a blend of b_k seconds
// centred on the waypoint's nominal time t_k (at a stop, from or to rest). The arm does not
// stop at a via waypoint; it cuts the corner and passes within
//
//   |q_j(t_k) - q_kj| = |v_kj - v_{k-1}j| b_k / 8  <=  a_j b_k^2 / 8     (joint j)
//
// of it (the blend's corner deviation, reported by via_deviation()). T_s starts at the
// slowest joint's time at full speed (and at least the waypoint's min_duration); segments
// next to a corner that needs more room are then lengthened until every blend satisfies
//
//   b_k = max_j |v_kj - v_{k-1}j| / a_j  <=  min(T_{k-1}, T_k)
//
// (a blend takes at most half of either neighbouring segment, so blends never overlap), with
// a guaranteed-feasible fallback (docs/trajectory.md). So |qd_j| <= v_j and |qdd_j| <= a_j hold
// everywhere, the path stays within the box of its neighbouring waypoints (within the joint
// limits), and a run with no via waypoint is exactly the stop-at-every-waypoint profile. Not
// time-optimal (a corner slows both its segments by the same factor), but never slower than
// stopping: a run that would be is split by stopping at its sharpest corner (that waypoint's
// passes_through() is then false) and each half is timed again.
//
// Determinism. Only +, -, *, / and sqrt (IEEE-754 exact), per-joint scalar loops or
// coefficient-wise Eigen expressions, no reductions whose order could change (max is
// order-independent), SSE2 arithmetic (x86-64: no x87 extended precision), and the trajectory
// sources are compiled with -ffp-contract=off (no fused multiply-add even under -march=native;
// never -ffast-math): the same waypoints and options give bit-identical trajectories on any
// x86-64 build (golden hashes in tests/core/plan_hash_test.cpp guard it).
//
// Shapes. A joint vector is dof() long, radians (revolute) or metres (prismatic); velocities
// per second, accelerations per second squared. TimedWaypoints holds N times and N joint
// vectors. Waypoints and samples are numbered from 0 in messages ("waypoint[3]"), joints from
// 1 ("joint 2 (shoulder)"), as everywhere else in telear.

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

#include "telear/core/blended_run.hpp"
#include "telear/core/result.hpp"
#include "telear/core/robot_model.hpp"
#include "telear/core/trapezoidal_profile.hpp"

namespace telear::core {

struct JointWaypoint {
  JointWaypoint() = default;
  // Implicit, so that a list of joint vectors reads {{q0}, {q1}, {q2, 1.5}}.
  JointWaypoint(Eigen::VectorXd q_,
                double min_duration_ = 0.0,  // NOLINT(google-explicit-constructor)
                std::optional<double> gripper_ = std::nullopt, bool via_ = false)
      : q(std::move(q_)), min_duration(min_duration_), gripper(gripper_), via(via_) {}

  Eigen::VectorXd q;
  // Lower bound on the time from the previous waypoint to this one (s); ignored on the first.
  // A waypoint repeated with a min_duration is a dwell (e.g. while the gripper closes).
  double min_duration = 0.0;
  // Gripper opening commanded on arrival at this waypoint, 0 (closed) .. 1 (open); unset:
  // unchanged. On a via waypoint: at its nominal time (waypoint_times()).
  std::optional<double> gripper;
  // Pass through without stopping (blend; see the top of this file). Ignored on the first and
  // last waypoints, and on a waypoint whose segment before or after does not move: the arm is
  // at rest there anyway.
  bool via = false;
  // Reach this waypoint with the tool on the straight line from the previous waypoint's tool
  // pose (MoveIt's Cartesian path) rather than on the straight line in joint space.
  // Trajectory::create first expands such a segment into joint via points that follow the
  // line, and refuses one that cannot be followed (telear/core/cartesian_segment.hpp). Ignored
  // on the first waypoint.
  bool cartesian = false;
  // Set on the via points that expansion inserts: not the operator's. A plan message leaves
  // them out, and Trajectory::create drops and recomputes them when it is given them back.
  bool expanded = false;
};

// The smallest velocity or acceleration scale: a thousandth of the joints' limits.
inline constexpr double kMinMotionScale = 1e-3;

struct TrajectoryOptions {
  double velocity_scale = 1.0;  // [0.001, 1]: fraction of each joint's max velocity to plan with
  double acceleration_scale = 1.0;  // [0.001, 1]: fraction of each joint's max acceleration
  int max_waypoints = 10000;
  double max_segment_duration = 3600.0;  // s; upper bound on a waypoint's min_duration
};

// A gripper command at a time of the trajectory.
struct GripperEvent {
  double time = 0.0;     // s from the start of the trajectory
  double opening = 0.0;  // 0 (closed) .. 1 (open)
};

// The sampled form of a trajectory: q[k] is the joint vector at times[k] (s from the start).
// Times strictly increase; the arm is at rest before the first and after the last sample.
struct TimedWaypoints {
  std::vector<double> times;
  std::vector<Eigen::VectorXd> q;
  std::vector<GripperEvent> gripper;  // in time order, each within [times.front(), times.back()]
};

struct TrajectoryPoint {
  Eigen::VectorXd q, qd, qdd;
};

inline constexpr int kMaxTimedSamples = 100000;  // 1000 s at 100 Hz

class Trajectory {
 public:
  // Validates the waypoints (validate_waypoints) and times them. Error messages say which
  // waypoint and joint, the value and the limit.
  static Result<Trajectory> create(const RobotModel& model, std::vector<JointWaypoint> waypoints,
                                   const TrajectoryOptions& options = {});

  int dof() const { return dof_; }
  double duration() const { return times_.back(); }
  const std::vector<JointWaypoint>& waypoints() const { return waypoints_; }
  // times()[k] is when the arm is at waypoint k: at rest at a stop waypoint (times()[0] == 0),
  // at the middle of its blend (its nominal time) at a via waypoint.
  const std::vector<double>& waypoint_times() const { return times_; }
  // One per segment. Between two stops, the segment's trapezoid; in a blended run (a segment
  // next to a via waypoint), a profile with the segment's duration, ramp 0, peak_rate
  // 1 / T_s (joint velocity D_j / T_s on the linear part) and acceleration 0: the blends'
  // accelerations are in peak_accelerations().
  const std::vector<TrapezoidalProfile>& segment_profiles() const { return profiles_; }

  // Whether the arm passes waypoint k without stopping (its `via` flag, unless ignored: first
  // or last waypoint, or a stationary segment next to it).
  bool passes_through(std::size_t k) const { return via_.at(k) != 0; }
  // |q(waypoint_times()[k]) - waypoints()[k].q| per joint, exact up to rounding: zero at a
  // stop, the blend's corner deviation |v_k - v_{k-1}| b_k / 8 at a via waypoint.
  Eigen::VectorXd via_deviation(std::size_t k) const;
  // The largest |qd_j| and |qdd_j| over the whole trajectory, per joint (analytic: the profile
  // is piecewise quadratic, so they are attained on its pieces' ends).
  Eigen::VectorXd peak_velocities() const;
  Eigen::VectorXd peak_accelerations() const;

  // What the trajectory was timed with: the options and the model's limits times the scales.
  const TrajectoryOptions& options() const { return options_; }
  const Eigen::VectorXd& velocity_limits() const { return v_max_; }
  const Eigen::VectorXd& acceleration_limits() const { return a_max_; }

  // Position, velocity and acceleration at time t (s), clamped to [0, duration()]: before
  // the start the arm rests at the first waypoint, after the end at the last. At t equal to
  // a stop waypoint's time q is that waypoint exactly. Outputs are resized to dof() (no
  // allocation when already that size); qd and qdd may be null.
  void sample(double t, Eigen::VectorXd& q, Eigen::VectorXd* qd = nullptr,
              Eigen::VectorXd* qdd = nullptr) const;
  TrajectoryPoint sample(double t) const;

  // The gripper opening last commanded at or before t, if any waypoint up to t commands one.
  std::optional<double> gripper_at(double t) const;
  std::vector<GripperEvent> gripper_events() const;

  // Samples at rate_hz (> 0): each segment is split into equal steps of at most 1 / rate_hz,
  // so every waypoint time (and its gripper command) falls on a sample. Fails when the rate
  // is not a positive finite number or when more than max_samples samples would be needed.
  Result<TimedWaypoints> sampled(double rate_hz, int max_samples = kMaxTimedSamples) const;

 private:
  // A piece of the profile from `start` to the next piece's start. segment >= 0: that
  // stop-to-stop segment, sampled through its trapezoid. Otherwise a quadratic in time,
  // q(t) = p + v (t - anchor) + a (t - anchor)^2 / 2, anchored where it is exact (a stop
  // waypoint at rest, or a via waypoint's nominal time).
  struct Piece {
    double start = 0.0;
    int segment = -1;
    double anchor = 0.0;
    Eigen::VectorXd p, v, a;
  };
  Trajectory() = default;
  TrapezoidalProfile stop_profile(std::size_t k) const;  // waypoint k -> k + 1, both stops
  void add_stop_segment(std::size_t k);
  // Waypoints first and last are stops, those between via points (first + 1 < last allowed).
  void add_run(std::size_t first, std::size_t last);
  void add_blended_run(std::size_t first, std::size_t last,
                       const std::vector<Eigen::VectorXd>& points, const BlendedRun& run);
  void add_quadratic(double start, double anchor, Eigen::VectorXd p, Eigen::VectorXd v,
                     Eigen::VectorXd a);

  int dof_ = 0;
  TrajectoryOptions options_;
  Eigen::VectorXd v_max_, a_max_;
  std::vector<JointWaypoint> waypoints_;
  std::vector<double> times_;                 // one per waypoint
  std::vector<char> via_;                     // one per waypoint: passed through
  std::vector<Eigen::VectorXd> deviation_;    // one per waypoint: via_deviation()
  std::vector<TrapezoidalProfile> profiles_;  // one per segment (waypoints - 1)
  std::vector<double> piece_starts_;          // pieces_[i].start, for the binary search
  std::vector<Piece> pieces_;
};

// Checks waypoints from an untrusted source: at least one and at most options.max_waypoints,
// each of dof() finite values within the joint limits, min_duration finite in
// [0, max_segment_duration], gripper opening finite in [0, 1]; and the options themselves.
Status validate_waypoints(const RobotModel& model, const std::vector<JointWaypoint>& waypoints,
                          const TrajectoryOptions& options = {});

struct TimedWaypointsLimits {
  int max_samples = kMaxTimedSamples;
  // Velocities and accelerations may exceed the model's limits by this fraction, to absorb
  // rounding (a trajectory from Trajectory::sampled stays within them exactly in theory). The
  // wire format rounds sample times to nanoseconds; second differences over 10 ms samples
  // turn that into relative errors of ~1e-6 at the limit, so the default leaves room: 1e-4
  // (0.01 %) is far below anything a servo or a motor could tell apart.
  double relative_tolerance = 1e-4;
};

// Checks a sampled trajectory from an untrusted sender, in this order: 1..max_samples samples,
// as many joint vectors as times; per sample: finite time, the first >= 0, each later one
// strictly greater; dof() finite values within the joint limits; between consecutive samples
// the mean velocity |dq / dt| within each joint's max velocity; at each sample the change of
// mean velocity over the mean of the two intervals within each joint's max acceleration,
// counting the arm at rest before the first and after the last sample (so it must start and
// end at rest); gripper events finite, in order, within the samples' time span, opening in
// [0, 1]. For a profile whose acceleration is bounded by a these finite differences are bounded
// by a too, so sampling a valid trajectory at any rate passes.
Status validate_timed_waypoints(const RobotModel& model, const TimedWaypoints& waypoints,
                                const TimedWaypointsLimits& limits = {});

}  // namespace telear::core
