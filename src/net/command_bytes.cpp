#include "telear/net/command_bytes.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>

#include "telear/core/clock.hpp"
#include "telear/net/plan_message.hpp"
#include "telear/net/robot_messages.hpp"
#include "telear/v1/robot.pb.h"

namespace telear::net {

namespace {

// A server clock reading typical of a machine up for a day (monotonic ns since boot): the
// expiry is a varint, so its size depends on the magnitude; a fixed value keeps the figure
// reproducible.
constexpr std::int64_t kServerNowNs = 86'400'000'000'000;
// How long each streamed jog stays valid (RobotClient::jog's default).
constexpr double kJogValidForS = 0.5;

// The plan's joint vector at time t by linear interpolation between its samples (clamped to
// its span). The jog stream only needs values of the right size and plausibility: a double
// costs 8 bytes on the wire whatever its value.
Eigen::VectorXd plan_at(const core::TimedWaypoints& plan, double t) {
  const auto& times = plan.times;
  if (t <= times.front()) return plan.q.front();
  if (t >= times.back()) return plan.q.back();
  const auto upper = std::upper_bound(times.begin(), times.end(), t);
  const std::size_t k = static_cast<std::size_t>(upper - times.begin());
  const double u = (t - times[k - 1]) / (times[k] - times[k - 1]);
  return plan.q[k - 1] + u * (plan.q[k] - plan.q[k - 1]);
}

}  // namespace

CommandBytes compare_command_bytes(const core::TimedWaypoints& plan, double jog_rate_hz,
                                   const std::string& lease_id, const std::string& trajectory_id) {
  assert(jog_rate_hz > 0.0 && std::isfinite(jog_rate_hz));
  CommandBytes bytes;
  v1::ExecuteTrajectoryRequest execute;
  execute.set_lease_id(lease_id);
  fill_trajectory_request(trajectory_id, plan, execute);
  bytes.plan_bytes = execute.ByteSizeLong();

  const std::size_t n = std::min(plan.times.size(), plan.q.size());
  if (n == 0) return bytes;
  const double start = plan.times.front();
  const double span = plan.times[n - 1] - start;
  // Samples at 0, 1/rate, ... up to and including the end (a small tolerance so that a span
  // of exactly k / rate gives k + 1 samples despite rounding).
  const int messages = static_cast<int>(std::floor(span * jog_rate_hz + 1e-9)) + 1;
  v1::JogRequest jog;
  for (int k = 0; k < messages; ++k) {
    const double t = start + k / jog_rate_hz;
    jog.Clear();
    jog.set_lease_id(lease_id);
    jog.set_expires_ns(kServerNowNs + core::s_to_ns(t - start + kJogValidForS));
    fill_jog_request(core::JointTarget{plan_at(plan, t)}, jog);
    bytes.jog_stream_bytes += jog.ByteSizeLong();
  }
  bytes.jog_messages = messages;
  return bytes;
}

Result<std::uint64_t> plan_message_bytes(const core::Trajectory& trajectory,
                                         const std::string& lease_id, const std::string& plan_id) {
  v1::ExecutePlanRequest request;
  request.set_lease_id(lease_id);
  if (Status s = fill_plan_message(plan_id, trajectory, *request.mutable_plan()); !s) {
    return s.error();
  }
  return static_cast<std::uint64_t>(request.ByteSizeLong());
}

}  // namespace telear::net
