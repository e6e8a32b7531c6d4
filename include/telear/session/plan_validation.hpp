#pragma once
// The checks a plan passes before it is executed, each turned into an issue the operator can
// act on. Errors block execution; warnings are shown and do not.
//
// Errors
//   - the plan is empty;
//   - a waypoint with the wrong size, a non-finite value, a joint beyond its limits, a
//     duration or gripper opening out of range (names the waypoint and the joint);
//   - a Cartesian segment the arm cannot follow (core/cartesian_segment.hpp): one error per
//     segment, at its first waypoint, saying where on the line and why (out of reach, a joint
//     that jumps, another IK configuration at its end);
//   - the plan cannot be timed within the joint velocity / acceleration limits at its scales
//     (core Trajectory::create), or its sampled form, the message actually sent, fails the
//     check the robot server applies (core validate_timed_waypoints: velocities, accelerations,
//     sample count);
//   - the plan's first waypoint is farther than start_tolerance from the real robot's current
//     q on some joint: the server would refuse it, and the arm would jump;
//   - with a collision checker: a contact anywhere along the timed trajectory, checked
//     continuously (geometry/trajectory_collision.hpp), one error per contact naming the
//     segment, the time, the link, the object (or other link) and the penetration depth;
//     with the workspace too, the same for an object the plan carries in the gripper
//     (session/plan_collision.hpp: check_carried_objects), named as the body.
// Warnings
//   - the real robot's state is unknown (the start was not checked);
//   - a single waypoint (executing it moves nothing);
//   - a segment passing near a singularity (smallest singular value of the geometric Jacobian
//     below singularity_warning_threshold, sampled along the straight joint-space segment,
//     or at the joint points of a Cartesian segment's expansion): a
//     joint path is safe there, but the Cartesian frame loses a direction, so the operator
//     should look at that part of the preview;
//   - with a collision checker: the arm passing closer to a workspace object than
//     safety_margin_m (where and how close).
//
// Reachability needs no IK here: waypoints are joint vectors, checked against the limits
// (a Cartesian segment's line is followed by IK, in its expansion).
// Waypoints are numbered from 0 ("waypoint[2]"), joints from 1 ("joint 2 (shoulder)").

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "telear/core/workspace.hpp"
#include "telear/geometry/trajectory_collision.hpp"
#include "telear/session/plan.hpp"

namespace telear::session {

enum class IssueSeverity { kError, kWarning };

struct ValidationIssue {
  IssueSeverity severity = IssueSeverity::kError;
  int waypoint = -1;  // 0-based waypoint concerned (first of a segment), -1 for the whole plan
  int joint = -1;     // 0-based joint concerned, -1 when none
  std::string message;
};

struct ValidationReport {
  std::vector<ValidationIssue> issues;  // errors first, then warnings, each in plan order
  // The continuous collision check's result, when a checker was given and the plan could be
  // checked: the contacts (time, link, object, depth) and clearances behind the messages.
  std::optional<geometry::TrajectoryCheckReport> collision;

  bool ok() const { return error_count() == 0; }  // executable (warnings allowed)
  int error_count() const;
  int warning_count() const;
  // "2 errors, 1 warning:\n  error: ...\n  warning: ..." or "ok" / "ok, 1 warning: ...".
  std::string summary() const;
};

struct ValidationOptions {
  // Largest allowed |q_plan[0] - q_real| per joint (rad or m); the robot server's
  // start_tolerance (RobotInfo::start_tolerance) when the session knows it.
  double start_tolerance = 0.01;
  double singularity_warning_threshold = 0.01;  // as MotionOptions
  int singularity_samples = 16;                 // per segment, both ends included
  // The rate the session samples the trajectory at for ExecuteTrajectory (Hz), and the
  // server's sample limit.
  double sample_rate_hz = 100.0;
  int max_samples = core::kMaxTimedSamples;
  // The robot's collision checker in the workspace (geometry/collision_checker.hpp), or null
  // for no collision check. Not owned; validation poses it, so not shared between threads.
  geometry::CollisionChecker* collision_checker = nullptr;
  // The workspace the checker was built from, graspable objects included (not owned), or
  // null: with it an object the gripper closes on is checked while it is carried.
  const core::Workspace* workspace = nullptr;
  // A clearance to a workspace object below this (m, >= 0) is a warning.
  double safety_margin_m = 0.03;
  geometry::TrajectoryCheckOptions collision_check;  // how finely the plan is checked
};

// `q_real`: the real robot's current joint vector, when known (from its state stream; an
// invalid one is reported as an error).
ValidationReport validate_plan(const Plan& plan, const std::optional<Eigen::VectorXd>& q_real,
                               const ValidationOptions& options = {});

const char* to_string(IssueSeverity severity);

}  // namespace telear::session
