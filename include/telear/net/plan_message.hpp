#pragma once
// The plan message (proto/telear/v1/robot.proto, PlanMessage): the operator's waypoints,
// timing parameters, id and the hash of the trajectory the client previewed, instead of the
// sampled trajectory. Both ends time it with core's Trajectory::create and fingerprint it with
// plan_hash (telear/core/plan_hash.hpp):
//
//   client  fill_plan_message(id, trajectory)      -> PlanMessage (hash = plan_hash(trajectory);
//                                                     the operator's waypoints only, a
//                                                     Cartesian segment's expanded points left out)
//   server  plan_from_message(model, message, ...) -> the same Trajectory, checked
//
// plan_from_message treats the message as untrusted and checks, in this order, each with a
// message "plan 'p1' rejected: ...": the id (as a trajectory id); the algorithm (only
// kTrajectoryAlgorithm is known); 1..max_waypoints waypoints; each waypoint's joint vector
// (size, finite values, limits), min_duration and gripper opening, and the scales
// (core::validate_waypoints, so the messages name waypoint and joint); the Cartesian
// segments, expanded as the client expanded them (core/cartesian_segment.hpp: a line the arm
// cannot follow is refused, naming the waypoint, where on the line and why); the plan's length
// (what plan_hash can hash); and finally the hash: the server's must equal the client's, and
// the error gives both (in hex). The start state is the caller's to check (it needs the arm's
// state).

#include <cstddef>
#include <string>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/core/robot_model.hpp"
#include "telear/core/trajectory.hpp"
#include "telear/net/robot_command_validation.hpp"
#include "telear/v1/robot.pb.h"

namespace telear::net {

// The hash travels as the digest's 32 raw bytes (PlanMessage.plan_hash is `bytes`); the C++
// API, the logs and the messages show it as plan_hash's 64 lowercase hex digits.
inline constexpr std::size_t kPlanHashBytes = 32;
std::string plan_hash_hex(const std::string& bytes);
// Fails unless `hex` is 64 lowercase hex digits.
Result<std::string> plan_hash_bytes(const std::string& hex);

// `plan_id`, the waypoints, the options' scales and kTrajectoryAlgorithm into `message`,
// without a hash: what PreviewPlan takes from a client that does not time plans itself (or
// a plan too broken to time, so that the server says why).
void fill_plan_waypoints(const std::string& plan_id,
                         const std::vector<core::JointWaypoint>& waypoints,
                         const core::TrajectoryOptions& options, v1::PlanMessage& message);

// `plan_id`, the trajectory's waypoints and options, kTrajectoryAlgorithm and its plan_hash
// into `message`. Fails only when the trajectory is too long to hash.
Status fill_plan_message(const std::string& plan_id, const core::Trajectory& trajectory,
                         v1::PlanMessage& message);

// check_trajectory_id's rules (plan and trajectory ids share one space), worded for a plan:
// "plan rejected: its id is empty".
Status check_plan_id(const std::string& id, const CommandLimits& limits);

struct ReceivedPlan {
  core::Trajectory trajectory;
  std::string hash;  // the server's, hex; equal to the client's unless PlanHashCheck::kIgnore
};

// kIgnore: PreviewPlan, which answers the hash instead of checking the client's.
enum class PlanHashCheck { kCompare, kIgnore };

Result<ReceivedPlan> plan_from_message(const core::RobotModel& model,
                                       const v1::PlanMessage& message, const CommandLimits& limits,
                                       PlanHashCheck check = PlanHashCheck::kCompare);

}  // namespace telear::net
