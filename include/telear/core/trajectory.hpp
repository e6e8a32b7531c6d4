#pragma once
// Joint waypoints -> a time-parameterized trajectory within each joint's velocity and
// acceleration limits, its sampled form (what crosses the network as one message), and the
// validation of both when they come from an untrusted sender.
//
// Profile. The arm stops at every waypoint. Between waypoints k and k+1 all joints share one
// trapezoidal time scaling s(t) in [0, 1] (telear/core/trapezoidal_profile.hpp):
//
//   q(t) = q_k + (q_{k+1} - q_k) s(t - t_k)
//
// so every joint starts and finishes the segment together and the path is the straight line
// in joint space whatever the speed (the preview, the singularity check and the real arm all
// follow the same path). The joint that needs longest, at its own max velocity or max
// acceleration, sets the segment's duration; the others move proportionally slower. A
// waypoint's min_duration stretches its segment (lower cruise speed, same ramps).
//
// Shapes. A joint vector is dof() long, radians (revolute) or metres (prismatic); velocities
// per second, accelerations per second squared. TimedWaypoints holds N times and N joint
// vectors. Waypoints and samples are numbered from 0 in messages ("waypoint[3]"), joints from
// 1 ("joint 2 (shoulder)"), as everywhere else in telear.

#include <Eigen/Core>
#include <optional>
#include <utility>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/core/robot_model.hpp"
#include "telear/core/trapezoidal_profile.hpp"

namespace telear::core {

struct JointWaypoint {
  JointWaypoint() = default;
  // Implicit, so that a list of joint vectors reads {{q0}, {q1}, {q2, 1.5}}.
  JointWaypoint(Eigen::VectorXd q_,
                double min_duration_ = 0.0,  // NOLINT(google-explicit-constructor)
                std::optional<double> gripper_ = std::nullopt)
      : q(std::move(q_)), min_duration(min_duration_), gripper(gripper_) {}

  Eigen::VectorXd q;
  // Lower bound on the time from the previous waypoint to this one (s); ignored on the first.
  // A waypoint repeated with a min_duration is a dwell (e.g. while the gripper closes).
  double min_duration = 0.0;
  // Gripper opening commanded on arrival at this waypoint, 0 (closed) .. 1 (open); unset:
  // unchanged.
  std::optional<double> gripper;
};

struct TrajectoryOptions {
  double velocity_scale = 1.0;      // (0, 1]: fraction of each joint's max velocity to plan with
  double acceleration_scale = 1.0;  // (0, 1]: fraction of each joint's max acceleration
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
  // times()[k] is when the arm is at (and stops at) waypoint k; times()[0] == 0.
  const std::vector<double>& waypoint_times() const { return times_; }
  const std::vector<TrapezoidalProfile>& segment_profiles() const { return profiles_; }

  // Position, velocity and acceleration at time t (s), clamped to [0, duration()]: before
  // the start the arm rests at the first waypoint, after the end at the last. At t equal to
  // a waypoint's time q is that waypoint exactly. Outputs are resized to dof() (no allocation
  // when already that size); qd and qdd may be null.
  void sample(double t, Eigen::VectorXd& q, Eigen::VectorXd* qd = nullptr,
              Eigen::VectorXd* qdd = nullptr) const;
  TrajectoryPoint sample(double t) const;

  // The gripper opening last commanded at or before t, if any waypoint up to t commands one.
  std::optional<double> gripper_at(double t) const;
  std::vector<GripperEvent> gripper_events() const;

  // Samples at rate_hz (> 0): each segment is split into equal steps of at most 1 / rate_hz,
  // so every waypoint (and its gripper command) falls on a sample. Fails when the rate is
  // not a positive finite number or when more than max_samples samples would be needed.
  Result<TimedWaypoints> sampled(double rate_hz, int max_samples = kMaxTimedSamples) const;

 private:
  Trajectory() = default;
  int dof_ = 0;
  std::vector<JointWaypoint> waypoints_;
  std::vector<double> times_;                 // one per waypoint
  std::vector<TrapezoidalProfile> profiles_;  // one per segment (waypoints - 1)
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
