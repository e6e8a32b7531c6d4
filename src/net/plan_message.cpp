#include "telear/net/plan_message.hpp"

#include <utility>
#include <vector>

#include "telear/core/plan_hash.hpp"

namespace telear::net {
namespace {

// The client's hash as shown in a message: untrusted text, so non-printable bytes become '?'
// and anything past the 64 digits of a SHA-256 is cut.
std::string shown(const std::string& text) {
  std::string out = text.substr(0, 64);
  for (char& c : out) {
    if (c < 0x20 || c > 0x7e) c = '?';
  }
  return text.size() > 64 ? out + "..." : out;
}

}  // namespace

Status fill_plan_message(const std::string& plan_id, const core::Trajectory& trajectory,
                         v1::PlanMessage& message) {
  auto hash = core::plan_hash(trajectory);
  if (!hash) return hash.error();
  message.Clear();
  message.set_plan_id(plan_id);
  message.set_algorithm(std::string(core::kTrajectoryAlgorithm));
  message.set_velocity_scale(trajectory.options().velocity_scale);
  message.set_acceleration_scale(trajectory.options().acceleration_scale);
  for (const core::JointWaypoint& w : trajectory.waypoints()) {
    v1::PlanWaypoint* out = message.add_waypoints();
    out->mutable_q()->Add(w.q.data(), w.q.data() + w.q.size());
    out->set_min_duration_s(w.min_duration);
    out->set_via(w.via);
    if (w.gripper) {
      out->set_has_gripper(true);
      out->set_gripper_opening(*w.gripper);
    }
  }
  message.set_plan_hash(*hash);
  return Status::Ok();
}

Status check_plan_id(const std::string& id, const CommandLimits& limits) {
  Status s = check_trajectory_id(id, limits);
  if (s) return s;
  // Its message reads "trajectory rejected: <why>".
  const std::string& message = s.error().message;
  return Error{"plan rejected: " + message.substr(message.find(": ") + 2)};
}

Result<ReceivedPlan> plan_from_message(const core::RobotModel& model,
                                       const v1::PlanMessage& message,
                                       const CommandLimits& limits) {
  const std::string label = "plan '" + message.plan_id() + "' rejected: ";
  if (Status s = check_plan_id(message.plan_id(), limits); !s) return s.error();
  if (message.algorithm() != core::kTrajectoryAlgorithm) {
    return Error{label + "unknown time parameterization '" + message.algorithm() +
                 "': this server times plans with '" + std::string(core::kTrajectoryAlgorithm) +
                 "' only; re-plan with a client of the same telear version, or send the "
                 "sampled trajectory (ExecuteTrajectory)"};
  }
  const int n = message.waypoints_size();
  if (n == 0) return Error{label + "it has no waypoints"};
  if (n > limits.max_waypoints) {
    return Error{label + "it has " + std::to_string(n) + " waypoints, more than the maximum of " +
                 std::to_string(limits.max_waypoints)};
  }
  std::vector<core::JointWaypoint> waypoints;
  waypoints.reserve(static_cast<size_t>(n));
  for (const v1::PlanWaypoint& w : message.waypoints()) {
    core::JointWaypoint& out = waypoints.emplace_back(
        Eigen::Map<const Eigen::VectorXd>(w.q().data(), w.q_size()), w.min_duration_s());
    out.via = w.via();
    if (w.has_gripper()) out.gripper = w.gripper_opening();
  }
  core::TrajectoryOptions options;
  options.velocity_scale = message.velocity_scale();
  options.acceleration_scale = message.acceleration_scale();
  options.max_waypoints = limits.max_waypoints;
  // Sizes, finite values, joint limits, durations, gripper openings, scales.
  auto trajectory = core::Trajectory::create(model, std::move(waypoints), options);
  if (!trajectory) return Error{label + trajectory.error().message};
  auto hash = core::plan_hash(*trajectory);
  if (!hash) return Error{label + hash.error().message};
  if (*hash != message.plan_hash()) {
    return Error{label + "its hash does not match: the client's is '" + shown(message.plan_hash()) +
                 "', the server's is '" + *hash + "' (" + std::string(core::kTrajectoryAlgorithm) +
                 "); the two sides timed the waypoints differently, so the arm would not do what "
                 "was previewed"};
  }
  return ReceivedPlan{std::move(*trajectory), std::move(*hash)};
}

}  // namespace telear::net
