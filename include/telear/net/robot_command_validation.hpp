#pragma once
// Robot commands from the wire (untrusted) -> core types, checked whole before any motion.
//
// Every check returns an Error whose message says what and why, prefixed by the command
// ("trajectory 'p1' rejected: ...", "jog rejected: ..."); the robot service answers it with
// INVALID_ARGUMENT. What is checked:
//   trajectory  id: 1..max_trajectory_id_length printable ASCII characters; 1..max_waypoints
//               waypoints; then core's validate_timed_waypoints (finite times strictly
//               increasing from >= 0, dof finite values within the joint limits, mean
//               velocity and acceleration between samples within each joint's limits,
//               starting and ending at rest, gripper events in order within the time span);
//               and its first waypoint within start_tolerance of the CURRENT measured state
//               (check_start_state, which names the joint that deviates most and by how much).
//   jog         exactly one command; vectors of the right size (dof or 3), finite values, a
//               joint index in range; its expiry (server clock) not yet past and not more
//               than max_jog_duration ahead.
//   gripper     an opening in [0, 1].
// Message size is bounded by the gRPC server itself (RobotServerOptions::max_receive_bytes).
//
// Waypoint times arrive in ns from the trajectory's start and become seconds (a double holds
// ns exactly up to 104 days).

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>

#include "telear/core/motion_command.hpp"
#include "telear/core/result.hpp"
#include "telear/core/robot_model.hpp"
#include "telear/core/trajectory.hpp"
#include "telear/v1/robot.pb.h"

namespace telear::net {

struct CommandLimits {
  int max_waypoints = 10000;
  std::size_t max_trajectory_id_length = 128;
  std::int64_t max_jog_duration_ns = 10'000'000'000;  // a jog may not expire later than this
};

Status check_trajectory_id(const std::string& id, const CommandLimits& limits);

// The request's waypoints and gripper events, validated (not the start state: that needs the
// current state, see check_start_state).
Result<core::TimedWaypoints> timed_waypoints_from_request(
    const core::RobotModel& model, const v1::ExecuteTrajectoryRequest& request,
    const CommandLimits& limits);

// "trajectory 'p1' rejected: it starts 0.120 rad (6.88 deg) from the current state at
// joint 2 (shoulder) (tolerance 0.010 rad): the arm is at ..., the trajectory starts at ..."
Status check_start_state(const core::RobotModel& model, const std::string& trajectory_id,
                         const Eigen::VectorXd& start, const Eigen::VectorXd& current_q,
                         double tolerance);

// A jog is either a motion command (increment or target, telear/core/motion_command.hpp) or a joint
// velocity.
struct JogCommand {
  std::optional<core::MotionCommand> motion;
  Eigen::VectorXd velocity;  // set when `motion` is not
  std::string description;   // for the log: "joint_increment joint 1 by 0.0100"
};

Result<JogCommand> jog_command_from_request(const core::RobotModel& model,
                                            const v1::JogRequest& request);

// "jog ignored: it expired 12.3 ms before it arrived"
Status check_jog_expiry(std::int64_t expires_ns, std::int64_t now_ns, const CommandLimits& limits);

Status check_gripper_opening(double opening);

// The operator's ghost on a lease renewal: dof() finite values within the limits, the opening
// in [0, 1]. "ghost rejected: 5 joint values for a 6-joint arm"
Status check_ghost(const core::RobotModel& model, const Eigen::VectorXd& q, double gripper);

}  // namespace telear::net
