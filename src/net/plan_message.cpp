#include "telear/net/plan_message.hpp"

#include <cstddef>
#include <utility>
#include <vector>

#include "telear/core/plan_hash.hpp"

namespace telear::net {
namespace {

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

}  // namespace

std::string plan_hash_hex(const std::string& bytes) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out;
  out.reserve(2 * bytes.size());
  for (const char c : bytes) {
    const auto b = static_cast<unsigned char>(c);
    out += kDigits[b >> 4];
    out += kDigits[b & 0xf];
  }
  return out;
}

Result<std::string> plan_hash_bytes(const std::string& hex) {
  if (hex.size() != 2 * kPlanHashBytes) {
    return Error{"a plan hash is " + std::to_string(2 * kPlanHashBytes) +
                 " lowercase hex digits, got " + std::to_string(hex.size()) + " characters"};
  }
  std::string out(kPlanHashBytes, '\0');
  for (std::size_t i = 0; i < kPlanHashBytes; ++i) {
    const int high = hex_value(hex[2 * i]), low = hex_value(hex[2 * i + 1]);
    if (high < 0 || low < 0) {
      return Error{"a plan hash is lowercase hex digits; character " + std::to_string(2 * i + 1) +
                   " or " + std::to_string(2 * i + 2) + " is not one"};
    }
    out[i] = static_cast<char>(high * 16 + low);
  }
  return out;
}

void fill_plan_waypoints(const std::string& plan_id,
                         const std::vector<core::JointWaypoint>& waypoints,
                         const core::TrajectoryOptions& options, v1::PlanMessage& message) {
  message.Clear();
  message.set_plan_id(plan_id);
  message.set_algorithm(std::string(core::kTrajectoryAlgorithm));
  message.set_velocity_scale(options.velocity_scale);
  message.set_acceleration_scale(options.acceleration_scale);
  for (const core::JointWaypoint& w : waypoints) {
    if (w.expanded) continue;  // a Cartesian segment's points: the server expands it again
    v1::PlanWaypoint* out = message.add_waypoints();
    out->mutable_q()->Add(w.q.data(), w.q.data() + w.q.size());
    out->set_min_duration_s(w.min_duration);
    out->set_via(w.via);
    out->set_cartesian(w.cartesian);
    if (w.gripper) {
      out->set_has_gripper(true);
      out->set_gripper_opening(*w.gripper);
    }
  }
}

Status fill_plan_message(const std::string& plan_id, const core::Trajectory& trajectory,
                         v1::PlanMessage& message) {
  auto hash = core::plan_hash(trajectory);
  if (!hash) return hash.error();
  auto digest = plan_hash_bytes(*hash);
  if (!digest) return digest.error();
  fill_plan_waypoints(plan_id, trajectory.waypoints(), trajectory.options(), message);
  message.set_plan_hash(std::move(*digest));
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
                                       const v1::PlanMessage& message, const CommandLimits& limits,
                                       PlanHashCheck check) {
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
    out.cartesian = w.cartesian();
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
  const std::string& client = message.plan_hash();
  if (check == PlanHashCheck::kCompare &&
      (client.size() != kPlanHashBytes || plan_hash_hex(client) != *hash)) {
    // Shown in hex, as plan_hash gives it; a client's field of another length than a digest's
    // is cut (and its length said) so that the message stays short.
    std::string shown = "'" + plan_hash_hex(client.substr(0, kPlanHashBytes)) +
                        (client.size() > kPlanHashBytes ? "...'" : "'");
    if (client.size() != kPlanHashBytes) {
      shown += " (" + std::to_string(client.size()) + " bytes, not the " +
               std::to_string(kPlanHashBytes) + " of a SHA-256 digest)";
    }
    return Error{label + "its hash does not match: the client's is " + shown +
                 ", the server's is '" + *hash + "' (" + std::string(core::kTrajectoryAlgorithm) +
                 "); the two sides timed the waypoints differently, so the arm would not do what "
                 "was previewed"};
  }
  return ReceivedPlan{std::move(*trajectory), std::move(*hash)};
}

}  // namespace telear::net
