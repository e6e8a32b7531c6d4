#pragma once
// A plan: the operator's task as a list of joint waypoints recorded from ghost poses, edited
// by trial and error, then time-parameterized and sent to the robot as one message.
//
//   waypoint k = { q (dof() values, rad or m), gripper opening on arrival (0..1, optional:
//                  unset keeps the previous), min_duration (s from waypoint k - 1; stretches
//                  the segment, a repeated pose with a duration is a dwell), label (free text) }
//
// The plan maps one to one onto telear/core/trajectory.hpp's JointWaypoint list: trajectory() times
// it with the plan's velocity / acceleration scales (straight joint-space segments, or a
// straight line of the tool to a waypoint marked cartesian; the arm stops at every waypoint not
// marked via), timed_waypoints() samples it for ExecuteTrajectory. A Cartesian segment that
// cannot be followed makes trajectory() fail, saying where and why (so validation and the
// preview report it).
//
// Editing keeps the plan valid: every waypoint added or changed is checked (size, finite,
// within the joint limits, duration in [0, max_segment_duration], gripper in [0, 1]) and a
// rejected edit changes nothing. Waypoints are numbered from 0 in messages ("waypoint[2]").
//
// File format (YAML; radians and seconds, the unit in every key's name):
//
//   robot: puma560                # must match the model the plan is loaded for
//   velocity_scale: 0.5           # optional, (0, 1], default 1
//   acceleration_scale: 0.5       # optional, (0, 1], default 1
//   waypoints:
//     - {label: approach, q_rad: [0, 0.5, -1.2, 0, 0.7, 0], gripper: 1}
//     - {q_rad: [0, 0.6, -1.1, 0, 0.5, 0], min_duration_s: 1.5, via: true}  # via: optional
//     - {q_rad: [0, 0.7, -1.0, 0, 0.4, 0]}
//     - {q_rad: [0.3, 0.7, -1.0, 0, 0.4, 0], cartesian: true}  # optional: tool on a line
//
// Files are untrusted: load errors name the file, the waypoint and the field.
//
// A plain value class, not thread-safe.

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/core/robot_model.hpp"
#include "telear/core/trajectory.hpp"

namespace telear::session {

class GhostArm;

struct PlanWaypoint {
  PlanWaypoint() = default;
  // Implicit, in JointWaypoint's order, so that {q}, {q, 1.5} and {q, 0.0, 1.0, "grasp"} read.
  PlanWaypoint(Eigen::VectorXd q_,  // NOLINT(google-explicit-constructor)
               double min_duration_ = 0.0, std::optional<double> gripper_ = std::nullopt,
               std::string label_ = {})
      : q(std::move(q_)),
        gripper(gripper_),
        min_duration(min_duration_),
        label(std::move(label_)) {}

  Eigen::VectorXd q;              // rad or m
  std::optional<double> gripper;  // 0 closed .. 1 open; unset: unchanged
  double min_duration = 0.0;      // s, from the previous waypoint
  std::string label;              // e.g. "approach"; may be empty
  bool via = false;               // pass through without stopping (core::JointWaypoint::via)
  // Reached with the tool on the straight line from the previous waypoint's tool pose
  // (core::JointWaypoint::cartesian, telear/core/cartesian_segment.hpp).
  bool cartesian = false;
};

class Plan {
 public:
  // `model` must not be null.
  explicit Plan(core::RobotModelPtr model);

  const core::RobotModel& model() const { return *model_; }
  const core::RobotModelPtr& model_ptr() const { return model_; }
  const std::vector<PlanWaypoint>& waypoints() const { return waypoints_; }
  const PlanWaypoint& waypoint(std::size_t index) const { return waypoints_.at(index); }
  std::size_t size() const { return waypoints_.size(); }
  bool empty() const { return waypoints_.empty(); }

  // Inserts before `index` (default: appends). Errors: invalid waypoint, index > size().
  Status add(PlanWaypoint waypoint, std::optional<std::size_t> index = std::nullopt);
  // The ghost's current pose, with its gripper opening when `with_gripper`.
  Status add_from(const GhostArm& ghost, double min_duration = 0.0, std::string label = {},
                  bool with_gripper = true, std::optional<std::size_t> index = std::nullopt);
  // Replaces waypoint `index` (e.g. with the ghost's corrected pose).
  Status replace(std::size_t index, PlanWaypoint waypoint);
  Status remove(std::size_t index);
  // Moves waypoint `from` so that it ends up at index `to` (both < size()).
  Status move(std::size_t from, std::size_t to);
  Status set_min_duration(std::size_t index, double seconds);
  Status set_gripper(std::size_t index, std::optional<double> opening);
  Status set_label(std::size_t index, std::string label);
  void clear() { waypoints_.clear(); }

  // Planning scales (TrajectoryOptions::velocity_scale / acceleration_scale), each in (0, 1].
  const core::TrajectoryOptions& trajectory_options() const { return options_; }
  Status set_scales(double velocity_scale, double acceleration_scale);

  // Checks one waypoint against the model and the plan's options; the message starts with
  // `where` (e.g. "waypoint[2]").
  Status check_waypoint(const PlanWaypoint& waypoint, const std::string& where) const;

  std::vector<core::JointWaypoint> joint_waypoints() const;
  // Errors: an empty plan; otherwise Trajectory::create's: a Cartesian segment that cannot be
  // followed (the others cannot happen for a plan edited through this class unless the
  // options changed). A plan with Cartesian segments times their expansion: the trajectory's
  // waypoints() then include the expanded via points (JointWaypoint::expanded).
  Result<core::Trajectory> trajectory() const;
  // trajectory() sampled at rate_hz (Trajectory::sampled).
  Result<core::TimedWaypoints> timed_waypoints(double rate_hz) const;

  // YAML text of the format above, and its parser; `source` names the text in messages.
  std::string to_yaml() const;
  static Result<Plan> from_yaml(core::RobotModelPtr model, const std::string& text,
                                const std::string& source = "plan");
  Status save(const std::string& path) const;
  static Result<Plan> load(core::RobotModelPtr model, const std::string& path);

 private:
  Status check_index(std::size_t index, const char* what) const;
  Status replace_as(std::size_t index, PlanWaypoint waypoint, const char* what);
  core::RobotModelPtr model_;
  core::TrajectoryOptions options_;
  std::vector<PlanWaypoint> waypoints_;
};

}  // namespace telear::session
