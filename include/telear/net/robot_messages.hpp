#pragma once
// Conversions between the robot service's wire messages (proto/telear/v1/robot.proto) and
// telear's own types (telear/core/robot_state.hpp, telear/core/robot_model.hpp), used by both the
// server and the client so the two sides cannot disagree. Pure functions, no validation: untrusted
// commands go through telear/net/robot_command_validation.hpp.

#include <string>

#include "telear/core/motion_command.hpp"
#include "telear/core/robot_model.hpp"
#include "telear/core/robot_state.hpp"
#include "telear/core/trajectory.hpp"
#include "telear/v1/robot.pb.h"

namespace telear::net {

v1::RobotMode to_proto(core::RobotMode mode);
core::RobotMode from_proto(v1::RobotMode mode);
v1::TrajectoryStatus to_proto(core::TrajectoryStatus status);
core::TrajectoryStatus from_proto(v1::TrajectoryStatus status);

// Joint names, limits and named configurations of `model` into `info`.
void fill_model_info(const core::RobotModel& model, v1::RobotInfo& info);

// The driver state into `message` (everything but sequence, capture and send times, lease
// holder and last trajectory, which the service knows).
void fill_state(const core::RobotState& state, v1::RobotState& message);

// The message back into a RobotState; `time` = capture_ns in seconds (server clock).
core::RobotState state_from_proto(const v1::RobotState& message);

// The motion of `command` into the request's `command` oneof (lease id and expiry are the
// caller's: they depend on the lease and the server clock).
void fill_jog_request(const core::MotionCommand& command, v1::JogRequest& request);

// `trajectory_id` and the samples and gripper events of `waypoints` (times in ns from the
// start, rounded) into `request`; the lease id is the caller's. Samples beyond the shorter of
// times and q are dropped (validation on the server rejects such a trajectory anyway).
void fill_trajectory_request(const std::string& trajectory_id,
                             const core::TimedWaypoints& waypoints,
                             v1::ExecuteTrajectoryRequest& request);

}  // namespace telear::net
