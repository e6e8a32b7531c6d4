#include "telear/core/trajectory.hpp"

#include "telear/core/number_format.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <string>

#include "telear/core/blended_run.hpp"
#include "telear/core/cartesian_segment.hpp"
#include "telear/core/joint_limits.hpp"

namespace telear::core {
namespace {

// A segment whose joints all move less than this (rad or m) is treated as not moving: its
// duration is its min_duration and the arm steps to the next waypoint at its end. Far below
// any encoder's resolution, it keeps 1 / displacement from overflowing.
constexpr double kStationaryDisplacement = 1e-12;
// A blended run this close to stopping's duration (relative) counts as no slower.
constexpr double kSameDuration = 1.0 + 1e-12;

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
  // At least a thousandth: a scale of 1e-314 (found by fuzzing the robot server) times out
  // every segment to infinity, and the trajectory's duration to NaN.
  auto in_range = [](double x) { return std::isfinite(x) && x >= kMinMotionScale && x <= 1.0; };
  if (!in_range(o.velocity_scale)) {
    return Error{"velocity_scale must be in [0.001, 1], got " + format_number(o.velocity_scale)};
  }
  if (!in_range(o.acceleration_scale)) {
    return Error{"acceleration_scale must be in [0.001, 1], got " +
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
  // The operator's waypoints are checked (their indices in the messages), then Cartesian
  // segments become joint via points, recomputed when given back expanded.
  waypoints = without_expanded_points(std::move(waypoints));
  if (Status s = validate_waypoints(model, waypoints, options); !s) return s.error();
  if (has_cartesian_segments(waypoints)) {
    auto expanded = expand_cartesian_segments(model, std::move(waypoints), options);
    if (!expanded) return expanded.error();
    waypoints = std::move(*expanded);
  }
  Trajectory trajectory;
  trajectory.dof_ = model.dof();
  trajectory.options_ = options;
  trajectory.v_max_ = options.velocity_scale * model.max_velocities();
  trajectory.a_max_ = options.acceleration_scale * model.max_accelerations();
  trajectory.waypoints_ = std::move(waypoints);
  const std::vector<JointWaypoint>& w = trajectory.waypoints_;
  const size_t n = w.size();
  // Which waypoints are passed through: a via flag inside the list with motion on both sides.
  auto moving = [&](size_t k) {  // segment k -> k + 1
    return (w[k + 1].q - w[k].q).cwiseAbs().maxCoeff() > kStationaryDisplacement;
  };
  trajectory.via_.assign(n, 0);
  for (size_t k = 1; k + 1 < n; ++k) {
    trajectory.via_[k] = w[k].via && moving(k - 1) && moving(k) ? 1 : 0;
  }
  trajectory.deviation_.assign(n, Eigen::VectorXd::Zero(model.dof()));
  trajectory.times_.assign(n, 0.0);
  trajectory.profiles_.reserve(n - 1);
  for (size_t k = 0; k + 1 < n;) {
    size_t last = k + 1;  // the next stop
    while (trajectory.via_[last] != 0) ++last;
    trajectory.add_run(k, last);
    k = last;
  }
  trajectory.piece_starts_.reserve(trajectory.pieces_.size());
  for (const Piece& piece : trajectory.pieces_) trajectory.piece_starts_.push_back(piece.start);
  return trajectory;
}

TrapezoidalProfile Trajectory::stop_profile(size_t k) const {
  const Eigen::ArrayXd D = (waypoints_[k + 1].q - waypoints_[k].q).array().abs();
  double alpha = 0.0;  // s: the slowest joint's time at full speed
  double beta = 0.0;   // s^2: the slowest joint's displacement over acceleration
  if (D.maxCoeff() > kStationaryDisplacement) {
    alpha = (D / v_max_.array()).maxCoeff();
    beta = (D / a_max_.array()).maxCoeff();
  }
  return TrapezoidalProfile::Fastest(alpha, beta, step_min_duration(waypoints_, k + 1));
}

void Trajectory::add_run(size_t first, size_t last) {
  if (last == first + 1) {
    add_stop_segment(first);
    return;
  }
  const size_t n = last - first;  // segments
  std::vector<Eigen::VectorXd> points(n + 1);
  std::vector<double> min_durations(n);
  for (size_t i = 0; i <= n; ++i) points[i] = waypoints_[first + i].q;
  for (size_t s = 0; s < n; ++s) min_durations[s] = step_min_duration(waypoints_, first + s + 1);
  const BlendedRun run = time_blended_run(points, min_durations, v_max_, a_max_);
  // Never slower than stopping at every via point of the run: otherwise stop at the corner
  // that needs the most room and try the two halves again. Minimum durations that bind make
  // both equal up to rounding (kSameDuration), and then the arm should not stop.
  double stopping = 0.0;
  for (size_t k = first; k < last; ++k) stopping += stop_profile(k).duration;
  if (run.duration() <= stopping * kSameDuration) {
    add_blended_run(first, last, points, run);
    return;
  }
  const size_t corner = first + sharpest_corner(points, v_max_, a_max_);
  via_[corner] = 0;
  add_run(first, corner);
  add_run(corner, last);
}

void Trajectory::add_stop_segment(size_t k) {
  const TrapezoidalProfile profile = stop_profile(k);
  profiles_.push_back(profile);
  times_[k + 1] = times_[k] + profile.duration;
  Piece piece;
  piece.start = times_[k];
  piece.segment = static_cast<int>(k);
  pieces_.push_back(std::move(piece));
}

void Trajectory::add_quadratic(double start, double anchor, Eigen::VectorXd p, Eigen::VectorXd v,
                               Eigen::VectorXd a) {
  Piece piece;
  // Rounding may put a piece's computed start an ulp before its predecessor's (a blend that
  // fills its segment): keep the starts sorted for the binary search.
  piece.start = pieces_.empty() ? start : std::max(start, pieces_.back().start);
  piece.anchor = anchor;
  piece.p = std::move(p);
  piece.v = std::move(v);
  piece.a = std::move(a);
  pieces_.push_back(std::move(piece));
}

void Trajectory::add_blended_run(size_t first, size_t last,
                                 const std::vector<Eigen::VectorXd>& points,
                                 const BlendedRun& run) {
  const size_t n = last - first;  // segments
  const std::vector<double>& T = run.segment_durations;
  const std::vector<double>& b = run.blend_durations;
  const std::vector<Eigen::VectorXd>& v = run.velocities;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(dof_);

  // Nominal times: the line of segment s passes P_s at t[s] and P_{s+1} at t[s + 1].
  std::vector<double> t(n + 1);
  const double start = times_[first];
  t[0] = start + 0.5 * b[0];
  for (size_t s = 0; s < n; ++s) t[s + 1] = t[s] + T[s];
  const double end = t[n] + 0.5 * b[n];
  for (size_t k = 1; k < n; ++k) times_[first + k] = t[k];
  times_[last] = end;

  // From rest at P_0: accelerate at v_0 / b_0 (the line through P_0 at t_0 meets it at the
  // blend's end).
  Eigen::VectorXd a(dof_);
  for (int j = 0; j < dof_; ++j) a[j] = v[0][j] / b[0];
  add_quadratic(start, start, points[0], zero, a);
  for (size_t s = 0; s < n; ++s) {
    if (s > 0 && b[s] > 0.0) {  // the blend around via point s, centred on t[s]
      Eigen::VectorXd p(dof_), mean(dof_), deviation(dof_);
      for (int j = 0; j < dof_; ++j) {
        const double dv = v[s][j] - v[s - 1][j];
        a[j] = dv / b[s];
        deviation[j] = dv * b[s] / 8.0;
        p[j] = points[s][j] + deviation[j];
        mean[j] = 0.5 * (v[s - 1][j] + v[s][j]);
      }
      deviation_[first + s] = deviation.cwiseAbs();
      add_quadratic(t[s] - 0.5 * b[s], t[s], std::move(p), std::move(mean), a);
    }
    add_quadratic(t[s] + 0.5 * b[s], t[s], points[s], v[s], zero);  // the linear part
  }
  // To rest at P_n, anchored there so that the run ends on it exactly.
  for (int j = 0; j < dof_; ++j) a[j] = -v[n - 1][j] / b[n];
  add_quadratic(end - b[n], end, points[n], zero, a);

  for (size_t s = 0; s < n; ++s) {
    TrapezoidalProfile profile;
    profile.duration = times_[first + s + 1] - times_[first + s];
    profile.peak_rate = 1.0 / T[s];
    profiles_.push_back(profile);
  }
}

Eigen::VectorXd Trajectory::via_deviation(size_t k) const {
  return deviation_.at(k);
}

Eigen::VectorXd Trajectory::peak_velocities() const {
  Eigen::VectorXd peak = Eigen::VectorXd::Zero(dof_);
  for (size_t i = 0; i < pieces_.size(); ++i) {
    const Piece& piece = pieces_[i];
    const double end = i + 1 < pieces_.size() ? pieces_[i + 1].start : duration();
    for (int j = 0; j < dof_; ++j) {
      double v = 0.0;
      if (piece.segment >= 0) {
        const auto k = static_cast<size_t>(piece.segment);
        v = std::abs(waypoints_[k + 1].q[j] - waypoints_[k].q[j]) * profiles_[k].peak_rate;
      } else {  // linear in time: the largest at either end
        v = std::max(std::abs(piece.v[j] + piece.a[j] * (piece.start - piece.anchor)),
                     std::abs(piece.v[j] + piece.a[j] * (end - piece.anchor)));
      }
      peak[j] = std::max(peak[j], v);
    }
  }
  return peak;
}

Eigen::VectorXd Trajectory::peak_accelerations() const {
  Eigen::VectorXd peak = Eigen::VectorXd::Zero(dof_);
  for (size_t i = 0; i < pieces_.size(); ++i) {
    const Piece& piece = pieces_[i];
    const double end = i + 1 < pieces_.size() ? pieces_[i + 1].start : duration();
    if (!(end > piece.start)) continue;  // never sampled
    for (int j = 0; j < dof_; ++j) {
      double a = 0.0;
      if (piece.segment >= 0) {
        const auto k = static_cast<size_t>(piece.segment);
        a = std::abs(waypoints_[k + 1].q[j] - waypoints_[k].q[j]) * profiles_[k].acceleration;
      } else {
        a = std::abs(piece.a[j]);
      }
      peak[j] = std::max(peak[j], a);
    }
  }
  return peak;
}

void Trajectory::sample(double t, Eigen::VectorXd& q, Eigen::VectorXd* qd,
                        Eigen::VectorXd* qdd) const {
  assert(!std::isnan(t) && "Trajectory::sample(): t is NaN");
  q.resize(dof_);
  if (qd) qd->resize(dof_);
  if (qdd) qdd->resize(dof_);
  if (pieces_.empty() || t >= times_.back()) {  // also the single-waypoint trajectory
    q = waypoints_.back().q;
    if (qd) qd->setZero();
    if (qdd) qdd->setZero();
    return;
  }
  // The piece with start <= t < the next one's start; a zero-length piece is never chosen.
  t = std::max(t, 0.0);
  const auto next = std::upper_bound(piece_starts_.begin(), piece_starts_.end(), t);
  const Piece& piece = pieces_[static_cast<size_t>(next - piece_starts_.begin()) - 1];
  if (piece.segment < 0) {
    const double tau = t - piece.anchor;
    for (int j = 0; j < dof_; ++j) {
      q[j] = piece.p[j] + piece.v[j] * tau + 0.5 * piece.a[j] * tau * tau;
      if (qd) (*qd)[j] = piece.v[j] + piece.a[j] * tau;
      if (qdd) (*qdd)[j] = piece.a[j];
    }
    return;
  }
  const auto k = static_cast<size_t>(piece.segment);
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
      if (i == n && via_[k + 1] == 0) {
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
    if (n == 0 && via_[k + 1] == 0) out.q.back() = waypoints_[k + 1].q;  // zero-duration
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
