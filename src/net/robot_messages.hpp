#pragma once
// Conversions between the robot service's wire messages (proto/telear/v1/robot.proto) and
// telear's own types (sim/robot_state.hpp, core/robot_model.hpp), used by both the server and
// the client so the two sides cannot disagree. Pure functions, no validation: untrusted
// commands go through net/robot_command_validation.hpp.

#include <string>

#include "core/robot_model.hpp"
#include "sim/robot_state.hpp"
#include "telear/v1/robot.pb.h"

namespace telear::net {

v1::RobotMode to_proto(RobotMode mode);
RobotMode from_proto(v1::RobotMode mode);
v1::TrajectoryStatus to_proto(TrajectoryStatus status);
TrajectoryStatus from_proto(v1::TrajectoryStatus status);

// Joint names, limits and named configurations of `model` into `info`.
void fill_model_info(const RobotModel& model, v1::RobotInfo& info);

// The driver state into `message` (everything but sequence, capture and send times, lease
// holder and last trajectory, which the service knows).
void fill_state(const RobotState& state, v1::RobotState& message);

// The message back into a RobotState; `time` = capture_ns in seconds (server clock).
RobotState state_from_proto(const v1::RobotState& message);

}  // namespace telear::net
