#include "telear/core/trajectory.hpp"

#include "telear/core/number_format.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <string>

#include "telear/core/joint_limits.hpp"

namespace telear::core {
namespace {

// A segment whose joints all move less than this (rad or m) is treated as not moving: its
// duration is its min_duration and the arm steps to the next waypoint at its end. Far below
// any encoder's resolution, it keeps 1 / displacement from overflowing.
constexpr double kStationaryDisplacement = 1e-12;

std::string indexed(const char* what, size_t k) {
  return std::string(what) + "[" + std::to_string(k) + "]";
}

// "waypoint[3]: " + a joint-vector problem (size, finite values, limits), or an empty string.
std::string joint_vector_problem(const RobotModel& model, const Eigen::VectorXd& q) {
  if (q.size() != model.dof()) {
    return "expected " + std::to_string(model.dof()) + " joint values, got " +
           std::to_string(q.size());
  }
  for (int j = 0; j < model.dof(); ++j) {
    if (!std::isfinite(q[j])) {
      return joint_label(model, j) + " value is not a finite number: " + format_number(q[j]);
    }
  }
  if (const auto violation = first_limit_violation(model, q)) {
    return describe_violation(model, *violation);
  }
  return {};
}

Status check_options(const TrajectoryOptions& o) {
  auto in_unit_interval = [](double x) { return std::isfinite(x) && x > 0.0 && x <= 1.0; };
  if (!in_unit_interval(o.velocity_scale)) {
    return Error{"velocity_scale must be in (0, 1], got " + format_number(o.velocity_scale)};
  }
  if (!in_unit_interval(o.acceleration_scale)) {
    return Error{"acceleration_scale must be in (0, 1], got " +
                 format_number(o.acceleration_scale)};
  }
  if (o.max_waypoints < 1) {
    return Error{"max_waypoints must be at least 1, got " + std::to_string(o.max_waypoints)};
  }
  if (!(std::isfinite(o.max_segment_duration) && o.max_segment_duration >= 0.0)) {
    return Error{"max_segment_duration must be a non-negative finite number, got " +
                 format_number(o.max_segment_duration)};
  }
  return Status::Ok();
}

}  // namespace

Status validate_waypoints(const RobotModel& model, const std::vector<JointWaypoint>& waypoints,
                          const TrajectoryOptions& options) {
  if (Status s = check_options(options); !s) return s;
  if (waypoints.empty()) return Error{"a trajectory needs at least one waypoint, got none"};
  if (waypoints.size() > static_cast<size_t>(options.max_waypoints)) {
    return Error{"trajectory has " + std::to_string(waypoints.size()) +
                 " waypoints, more than the maximum of " + std::to_string(options.max_waypoints)};
  }
  for (size_t k = 0; k < waypoints.size(); ++k) {
    const JointWaypoint& w = waypoints[k];
    const std::string where = indexed("waypoint", k) + ": ";
    if (std::string problem = joint_vector_problem(model, w.q); !problem.empty()) {
      return Error{where + problem};
    }
    if (!std::isfinite(w.min_duration)) {
      return Error{where +
                   "minimum duration is not a finite number: " + format_number(w.min_duration)};
    }
    if (w.min_duration < 0.0) {
      return Error{where + "minimum duration " + format_seconds(w.min_duration) + " is negative"};
    }
    if (w.min_duration > options.max_segment_duration) {
      return Error{where + "minimum duration " + format_seconds(w.min_duration) +
                   " exceeds the maximum of " + format_seconds(options.max_segment_duration)};
    }
    if (w.gripper && !(std::isfinite(*w.gripper) && *w.gripper >= 0.0 && *w.gripper <= 1.0)) {
      return Error{where + "gripper opening " + format_number(*w.gripper) +
                   " is outside [0, 1] (0 closed, 1 open)"};
    }
  }
  return Status::Ok();
}

Result<Trajectory> Trajectory::create(const RobotModel& model, std::vector<JointWaypoint> waypoints,
                                      const TrajectoryOptions& options) {
  if (Status s = validate_waypoints(model, waypoints, options); !s) return s.error();
  Trajectory trajectory;
  trajectory.dof_ = model.dof();
  trajectory.times_.reserve(waypoints.size());
  trajectory.profiles_.reserve(waypoints.size() - 1);
  trajectory.times_.push_back(0.0);
  const Eigen::VectorXd v_max = options.velocity_scale * model.max_velocities();
  const Eigen::VectorXd a_max = options.acceleration_scale * model.max_accelerations();
  for (size_t k = 1; k < waypoints.size(); ++k) {
    const Eigen::ArrayXd D = (waypoints[k].q - waypoints[k - 1].q).array().abs();
    double alpha = 0.0;  // s: the slowest joint's time at full speed
    double beta = 0.0;   // s^2: the slowest joint's displacement over acceleration
    if (D.maxCoeff() > kStationaryDisplacement) {
      alpha = (D / v_max.array()).maxCoeff();
      beta = (D / a_max.array()).maxCoeff();
    }
    const TrapezoidalProfile profile =
        TrapezoidalProfile::Fastest(alpha, beta, waypoints[k].min_duration);
    trajectory.profiles_.push_back(profile);
    trajectory.times_.push_back(trajectory.times_.back() + profile.duration);
  }
  trajectory.waypoints_ = std::move(waypoints);
  return trajectory;
}

void Trajectory::sample(double t, Eigen::VectorXd& q, Eigen::VectorXd* qd,
                        Eigen::VectorXd* qdd) const {
  assert(!std::isnan(t) && "Trajectory::sample(): t is NaN");
  q.resize(dof_);
  if (qd) qd->resize(dof_);
  if (qdd) qdd->resize(dof_);
  if (t >= times_.back()) {  // also the single-waypoint trajectory
    q = waypoints_.back().q;
    if (qd) qd->setZero();
    if (qdd) qdd->setZero();
    return;
  }
  // Segment k with times_[k] <= t < times_[k + 1]; a zero-duration segment is never chosen.
  const auto next = std::upper_bound(times_.begin(), times_.end(), std::max(t, 0.0));
  const size_t k = static_cast<size_t>(next - times_.begin()) - 1;
  const Eigen::VectorXd& q0 = waypoints_[k].q;
  const Eigen::VectorXd& q1 = waypoints_[k + 1].q;
  double s = 0.0, s_dot = 0.0, s_ddot = 0.0;
  profiles_[k].sample(t - times_[k], s, s_dot, s_ddot);
  // Interpolate from the nearer end so that q is exact at both waypoints.
  if (s < 0.5) {
    q = q0 + (q1 - q0) * s;
  } else {
    q = q1 - (q1 - q0) * (1.0 - s);
  }
  if (qd) *qd = (q1 - q0) * s_dot;
  if (qdd) *qdd = (q1 - q0) * s_ddot;
}

TrajectoryPoint Trajectory::sample(double t) const {
  TrajectoryPoint point;
  sample(t, point.q, &point.qd, &point.qdd);
  return point;
}

std::optional<double> Trajectory::gripper_at(double t) const {
  std::optional<double> opening;
  for (size_t k = 0; k < waypoints_.size() && times_[k] <= t; ++k) {
    if (waypoints_[k].gripper) opening = waypoints_[k].gripper;
  }
  return opening;
}

std::vector<GripperEvent> Trajectory::gripper_events() const {
  std::vector<GripperEvent> events;
  for (size_t k = 0; k < waypoints_.size(); ++k) {
    if (waypoints_[k].gripper) events.push_back({times_[k], *waypoints_[k].gripper});
  }
  return events;
}

Result<TimedWaypoints> Trajectory::sampled(double rate_hz, int max_samples) const {
  if (!(std::isfinite(rate_hz) && rate_hz > 0.0)) {
    return Error{"sample rate must be a positive finite number of Hz, got " +
                 format_number(rate_hz)};
  }
  // Steps per segment, counted first so that an absurd request fails before allocating.
  std::vector<double> steps(profiles_.size());
  double total = 1.0;
  for (size_t k = 0; k < profiles_.size(); ++k) {
    steps[k] = std::ceil(profiles_[k].duration * rate_hz);
    total += steps[k];
  }
  if (total > max_samples) {
    return Error{"sampling the " + format_seconds(duration()) + " trajectory at " +
                 format_number(rate_hz) + " Hz needs " + format_number(total, "%.0f") +
                 " samples, more than the maximum of " + std::to_string(max_samples)};
  }
  TimedWaypoints out;
  out.times.reserve(static_cast<size_t>(total));
  out.q.reserve(static_cast<size_t>(total));
  out.times.push_back(0.0);
  out.q.push_back(waypoints_.front().q);
  Eigen::VectorXd q(dof_);
  for (size_t k = 0; k < profiles_.size(); ++k) {
    const double T = profiles_[k].duration;
    const auto n = static_cast<int>(steps[k]);
    for (int i = 1; i <= n; ++i) {
      // The last step lands exactly on the waypoint time computed in create().
      const double t = (i == n) ? times_[k + 1] : times_[k] + T * i / n;
      if (i == n) {
        q = waypoints_[k + 1].q;
      } else {
        sample(t, q);
      }
      if (t > out.times.back()) {
        out.times.push_back(t);
        out.q.push_back(q);
      } else {  // a step shorter than the clock's resolution: keep the later position
        out.q.back() = q;
      }
    }
    if (n == 0) out.q.back() = waypoints_[k + 1].q;  // zero-duration segment
  }
  out.gripper = gripper_events();
  return out;
}

Status validate_timed_waypoints(const RobotModel& model, const TimedWaypoints& w,
                                const TimedWaypointsLimits& limits) {
  const size_t n = w.times.size();
  if (n == 0) return Error{"timed waypoints: no samples"};
  if (n > static_cast<size_t>(limits.max_samples)) {
    return Error{"timed waypoints: " + std::to_string(n) + " samples, more than the maximum of " +
                 std::to_string(limits.max_samples)};
  }
  if (w.q.size() != n) {
    return Error{"timed waypoints: " + std::to_string(n) + " times but " +
                 std::to_string(w.q.size()) + " joint vectors"};
  }
  for (size_t k = 0; k < n; ++k) {
    const std::string where = indexed("sample", k) + ": ";
    const double t = w.times[k];
    if (!std::isfinite(t)) return Error{where + "time is not a finite number: " + format_number(t)};
    if (k == 0 && t < 0.0) {
      return Error{where + "time " + format_seconds(t) +
                   " is negative (times start at 0 or later)"};
    }
    if (k > 0 && !(t > w.times[k - 1])) {
      return Error{where + "time " + format_seconds(t) + " is not after the previous sample's " +
                   format_seconds(w.times[k - 1]) + " (times must strictly increase)"};
    }
    if (std::string problem = joint_vector_problem(model, w.q[k]); !problem.empty()) {
      return Error{where + problem};
    }
  }
  const double slack = 1.0 + limits.relative_tolerance;
  const int dof = model.dof();
  // Mean velocity over interval k (between samples k - 1 and k); 0 before and after.
  auto mean_velocity = [&](size_t k, int j) {
    if (k == 0 || k == n) return 0.0;
    return (w.q[k][j] - w.q[k - 1][j]) / (w.times[k] - w.times[k - 1]);
  };
  for (size_t k = 1; k < n; ++k) {
    for (int j = 0; j < dof; ++j) {
      const double v = mean_velocity(k, j);
      const double v_max = model.max_velocities()[j];
      if (std::abs(v) > v_max * slack) {
        return Error{indexed("sample", k - 1) + " to " + indexed("sample", k) +
                     " (t = " + format_seconds(w.times[k - 1]) + " to " +
                     format_seconds(w.times[k]) + "): " + joint_label(model, j) + " moves at " +
                     format_joint_value(model, j, v) + "/s, beyond its max velocity of " +
                     format_joint_value(model, j, v_max) + "/s"};
      }
    }
  }
  if (n >= 2) {
    auto interval = [&](size_t k) {
      return (k == 0 || k == n) ? 0.0 : w.times[k] - w.times[k - 1];
    };
    for (size_t k = 0; k < n; ++k) {
      // Intervals k (before sample k) and k + 1 (after it).
      const double h = 0.5 * (interval(k) + interval(k + 1));
      for (int j = 0; j < dof; ++j) {
        const double a = (mean_velocity(k + 1, j) - mean_velocity(k, j)) / h;
        const double a_max = model.max_accelerations()[j];
        if (std::abs(a) > a_max * slack) {
          const char* note =
              k == 0 ? ", starting from rest" : (k == n - 1 ? ", ending at rest" : "");
          return Error{indexed("sample", k) + " (t = " + format_seconds(w.times[k]) + note +
                       "): " + joint_label(model, j) + " accelerates at " +
                       format_joint_value(model, j, a) + "/s^2, beyond its max acceleration of " +
                       format_joint_value(model, j, a_max) + "/s^2"};
        }
      }
    }
  }
  for (size_t e = 0; e < w.gripper.size(); ++e) {
    const GripperEvent& g = w.gripper[e];
    const std::string where = indexed("gripper event", e) + ": ";
    if (!std::isfinite(g.time)) {
      return Error{where + "time is not a finite number: " + format_number(g.time)};
    }
    if (g.time < w.times.front() || g.time > w.times.back()) {
      return Error{where + "time " + format_seconds(g.time) + " is outside the samples' span " +
                   format_seconds(w.times.front()) + " to " + format_seconds(w.times.back())};
    }
    if (e > 0 && g.time < w.gripper[e - 1].time) {
      return Error{where + "time " + format_seconds(g.time) + " is before the previous event's " +
                   format_seconds(w.gripper[e - 1].time)};
    }
    if (!(std::isfinite(g.opening) && g.opening >= 0.0 && g.opening <= 1.0)) {
      return Error{where + "opening " + format_number(g.opening) +
                   " is outside [0, 1] (0 closed, 1 open)"};
    }
  }
  return Status::Ok();
}

}  // namespace telear::core
