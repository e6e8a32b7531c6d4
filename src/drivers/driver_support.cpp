#include "drivers/driver_support.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "telear/core/clock.hpp"
#include "telear/core/number_format.hpp"

namespace telear::drivers {

std::string quoted(const std::string& text) {
  return "'" + text + "'";
}

std::vector<std::string> joint_names(const core::RobotModel& model) {
  std::vector<std::string> names;
  for (const core::Joint& joint : model.joints()) names.push_back(joint.name);
  return names;
}

std::string joint_list(const std::vector<std::string>& names) {
  std::string list;
  for (const std::string& name : names) list += (list.empty() ? "" : ", ") + name;
  return list;
}

std::optional<Eigen::VectorXd> values_by_name(const std::vector<std::string>& wanted,
                                              const std::vector<std::string>& names,
                                              const std::vector<double>& values,
                                              std::string* missing) {
  Eigen::VectorXd out(static_cast<Eigen::Index>(wanted.size()));
  for (std::size_t j = 0; j < wanted.size(); ++j) {
    const auto at = std::find(names.begin(), names.end(), wanted[j]);
    const auto index = static_cast<std::size_t>(at - names.begin());
    if (at == names.end() || index >= values.size()) {
      if (missing != nullptr) *missing = wanted[j];
      return std::nullopt;
    }
    out[static_cast<Eigen::Index>(j)] = values[index];
  }
  return out;
}

Status check_jog_expiry(std::int64_t expires_ns, std::int64_t now_ns, double max_duration_s) {
  if (expires_ns <= now_ns) {
    return Error{"jog ignored: it expired " +
                 core::format_number(core::ns_to_s(now_ns - expires_ns), "%.3f s") +
                 " before it arrived"};
  }
  if (core::ns_to_s(expires_ns - now_ns) > max_duration_s) {
    return Error{"jog rejected: it expires " +
                 core::format_number(core::ns_to_s(expires_ns - now_ns), "%.3f s") +
                 " from now, later than the maximum of " +
                 core::format_number(max_duration_s, "%.3f s")};
  }
  return Status::Ok();
}

Status check_can_move(const std::string& what, bool estop, const std::string& estop_reason,
                      const std::optional<std::string>& running_id,
                      const std::optional<std::string>& fault) {
  if (estop) {
    return Error{what + " rejected: the e-stop is engaged (" + estop_reason +
                 "); reset it once the arm is at rest"};
  }
  if (running_id) {
    return Error{what + " rejected: trajectory " + quoted(*running_id) +
                 " is running; cancel it first or wait until it completes"};
  }
  if (fault) return Error{what + " rejected: " + *fault};
  return Status::Ok();
}

Status check_gripper_events_keep(const std::string& what,
                                 const std::vector<core::GripperEvent>& events, double opening,
                                 const std::string& why_none) {
  for (const core::GripperEvent& event : events) {
    if (std::abs(event.opening - opening) > 1e-9) {
      return Error{what + " rejected: it moves the gripper to " +
                   core::format_number(event.opening, "%.3f") + " at " +
                   core::format_number(event.time, "%.3f s") + ", and " + why_none};
    }
  }
  return Status::Ok();
}

GoalPoints goal_points(const core::TimedWaypoints& samples) {
  GoalPoints points;
  const double t0 = samples.times.empty() ? 0.0 : samples.times.front();
  for (std::size_t k = 0; k < samples.q.size(); ++k) {
    points.times_ns.push_back(std::llround((samples.times[k] - t0) * 1e9));
    const Eigen::VectorXd& q = samples.q[k];
    points.positions.emplace_back(q.data(), q.data() + q.size());
  }
  return points;
}

Result<GoalPoints> jog_points(const core::RobotModel& model, const Eigen::VectorXd& q,
                              const Eigen::VectorXd& target, std::optional<double> duration_s,
                              double rate_hz) {
  if (duration_s) return goal_points(core::TimedWaypoints{{0.0, *duration_s}, {q, target}, {}});
  auto timed = core::Trajectory::create(model, {{q}, {target}});
  if (!timed) return Error{"jog rejected: " + timed.error().message};
  auto samples = timed->sampled(rate_hz);
  if (!samples) return Error{"jog rejected: " + samples.error().message};
  return goal_points(*samples);
}

void PreviewPlayback::start(core::TimedWaypoints samples, std::int64_t now_ns) {
  samples_ = std::move(samples);
  started_ns_ = now_ns;
  next_ = 0;
  playing_ = !samples_.q.empty();
}

PreviewPlayback::Frame PreviewPlayback::advance(std::int64_t now_ns, double rate_hz) {
  const std::vector<double>& times = samples_.times;
  const double t = times.front() + core::ns_to_s(now_ns - started_ns_);
  std::size_t k = next_;
  while (k + 1 < times.size() && times[k + 1] <= t) ++k;
  Frame frame{samples_.q[k], std::nullopt};
  if (k + 1 >= times.size()) {
    playing_ = false;
  } else {
    next_ = k + 1;
    frame.next_ns = now_ns + core::s_to_ns(1.0 / rate_hz);
  }
  return frame;
}

}  // namespace telear::drivers
