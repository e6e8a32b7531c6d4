#pragma once
// What commanding a motion costs on the wire: the seed's point that sending one finalized
// trajectory beats streaming the operator's commands (and survives a bad network).
//
//   plan message     one ExecutePlanRequest: the waypoints, timing parameters and hash (the
//                    digest's 32 bytes); the server re-times them (telear/net/plan_message.hpp)
//   plan-then-send   one ExecuteTrajectoryRequest with the sampled trajectory
//   jogging          the same motion as a JogRequest (joint target, lease id, expiry) per
//                    sample at jog_rate_hz, as a conventional teleoperation client streams it
//
// Sizes are the serialized protobuf bytes (ByteSizeLong) of the requests telear's client
// sends, with a lease id of the server's length; gRPC/HTTP2 framing (~9 B per message plus
// headers) comes on top and favours the single message further.

#include <cstdint>
#include <string>

#include "telear/core/result.hpp"
#include "telear/core/trajectory.hpp"

namespace telear::net {

struct CommandBytes {
  std::uint64_t plan_bytes = 0;        // the one ExecuteTrajectoryRequest
  std::uint64_t jog_stream_bytes = 0;  // all JogRequests
  int jog_messages = 0;
};

// `plan` is the trajectory as sent (sampled); the jog stream samples the same span at
// jog_rate_hz (> 0), one joint-target jog per sample.
CommandBytes compare_command_bytes(const core::TimedWaypoints& plan, double jog_rate_hz,
                                   const std::string& lease_id, const std::string& trajectory_id);

// The bytes of the one ExecutePlanRequest that sends `trajectory` as a plan message. Fails
// when the trajectory is too long to hash (plan_hash).
Result<std::uint64_t> plan_message_bytes(const core::Trajectory& trajectory,
                                         const std::string& lease_id, const std::string& plan_id);

}  // namespace telear::net
