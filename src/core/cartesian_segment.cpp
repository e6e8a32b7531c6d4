#include "telear/core/cartesian_segment.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <utility>

#include "telear/core/inverse_kinematics.hpp"
#include "telear/core/joint_limits.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/number_format.hpp"

// Compiled with -ffp-contract=off like trajectory.cpp (src/core/CMakeLists.txt), and written
// with scalar arithmetic in a fixed order (no Eigen reductions, whose order depends on the
// vector width a build chose): the line's poses and the checks below are bit-identical in
// every x86-64 build.

namespace telear::core {
namespace {

// Two unit quaternions q, r (q . r >= 0) are an angle theta apart when q . r = cos(theta / 2).
constexpr double kCosHalfMaxStep = 0.9998476951563913;         // cos(1 deg): 2 deg steps
constexpr double kCosHalfChordTolerance = 0.9999996192282494;  // cos(0.05 deg): 0.1 deg
static_assert(kCartesianMaxStepRad == radians_from_degrees(2.0) &&
                  kCartesianChordToleranceRad == radians_from_degrees(0.1),
              "update the cosines above with the tolerances");
constexpr int kMaxLevel = 24;  // 2^24 steps of the line: beyond any max_waypoints in use

struct Quat {
  double w = 1.0, x = 0.0, y = 0.0, z = 0.0;
};

double dot(const Quat& a, const Quat& b) {
  return a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z;
}

Quat scaled(const Quat& q, double f) {
  return {q.w * f, q.x * f, q.y * f, q.z * f};
}

Quat normalized(const Quat& q) {
  return scaled(q, 1.0 / std::sqrt(dot(q, q)));
}

// The slerp midpoint of a and b (a . b >= 0, so |a + b| >= sqrt 2).
Quat midpoint(const Quat& a, const Quat& b) {
  return normalized({a.w + b.w, a.x + b.x, a.y + b.y, a.z + b.z});
}

// Shepperd's method: the largest of the four candidate divisors, for accuracy.
Quat quat_from_rotation(const Eigen::Matrix3d& R) {
  const double trace = R(0, 0) + R(1, 1) + R(2, 2);
  Quat q;
  if (trace > 0.0) {
    const double s = 2.0 * std::sqrt(trace + 1.0);
    q = {0.25 * s, (R(2, 1) - R(1, 2)) / s, (R(0, 2) - R(2, 0)) / s, (R(1, 0) - R(0, 1)) / s};
  } else if (R(0, 0) > R(1, 1) && R(0, 0) > R(2, 2)) {
    const double s = 2.0 * std::sqrt(1.0 + R(0, 0) - R(1, 1) - R(2, 2));
    q = {(R(2, 1) - R(1, 2)) / s, 0.25 * s, (R(0, 1) + R(1, 0)) / s, (R(0, 2) + R(2, 0)) / s};
  } else if (R(1, 1) > R(2, 2)) {
    const double s = 2.0 * std::sqrt(1.0 + R(1, 1) - R(0, 0) - R(2, 2));
    q = {(R(0, 2) - R(2, 0)) / s, (R(0, 1) + R(1, 0)) / s, 0.25 * s, (R(1, 2) + R(2, 1)) / s};
  } else {
    const double s = 2.0 * std::sqrt(1.0 + R(2, 2) - R(0, 0) - R(1, 1));
    q = {(R(1, 0) - R(0, 1)) / s, (R(0, 2) + R(2, 0)) / s, (R(1, 2) + R(2, 1)) / s, 0.25 * s};
  }
  return normalized(q);
}

Eigen::Matrix3d rotation_from_quat(const Quat& q) {
  Eigen::Matrix3d R;
  R(0, 0) = 1.0 - 2.0 * (q.y * q.y + q.z * q.z);
  R(0, 1) = 2.0 * (q.x * q.y - q.z * q.w);
  R(0, 2) = 2.0 * (q.x * q.z + q.y * q.w);
  R(1, 0) = 2.0 * (q.x * q.y + q.z * q.w);
  R(1, 1) = 1.0 - 2.0 * (q.x * q.x + q.z * q.z);
  R(1, 2) = 2.0 * (q.y * q.z - q.x * q.w);
  R(2, 0) = 2.0 * (q.x * q.z - q.y * q.w);
  R(2, 1) = 2.0 * (q.y * q.z + q.x * q.w);
  R(2, 2) = 1.0 - 2.0 * (q.x * q.x + q.y * q.y);
  return R;
}

std::string percent(double s) {
  return format_fixed(100.0 * s, 1) + " %";
}

// One segment's expansion: the points after A up to (not including) B.
class SegmentExpander {
 public:
  SegmentExpander(const RobotModel& model, KinematicsData& data, std::string where)
      : model_(model), data_(data), where_(std::move(where)) {}

  // Fills points(); `budget` is how many may be added before max_waypoints is exceeded.
  Status expand(const Eigen::VectorXd& qa, const Eigen::VectorXd& qb, std::size_t budget) {
    budget_ = budget;
    forward_kinematics(model_, data_, qa);
    pa_ = data_.T_base_tool.translation();
    const Quat Qa = quat_from_rotation(data_.T_base_tool.linear());
    forward_kinematics(model_, data_, qb);
    pb_ = data_.T_base_tool.translation();
    Quat Qb = quat_from_rotation(data_.T_base_tool.linear());
    if (dot(Qa, Qb) < 0.0) Qb = scaled(Qb, -1.0);  // the shorter arc

    // The smallest level k whose 2^k steps are short enough, by halving: step length
    // length / 2^k, and the cosine of half a step's turn from cos(x / 2) = sqrt((1 + cos x) / 2).
    const double dx = pb_[0] - pa_[0], dy = pb_[1] - pa_[1], dz = pb_[2] - pa_[2];
    length_ = std::sqrt(dx * dx + dy * dy + dz * dz);
    double step_length = length_;
    double cos_half_turn = std::min(1.0, dot(Qa, Qb));
    int level = 0;
    while (step_length > kCartesianMaxStepM || cos_half_turn < kCosHalfMaxStep) {
      if (level == kMaxLevel) return too_many(std::size_t{1} << kMaxLevel);
      ++level;
      step_length *= 0.5;
      cos_half_turn = std::sqrt((1.0 + cos_half_turn) * 0.5);
    }
    const std::size_t n = std::size_t{1} << level;
    if (n - 1 > budget_) return too_many(n);
    std::vector<Quat> Q(n + 1);
    Q[0] = Qa;
    Q[n] = Qb;
    for (std::size_t half = n / 2; half >= 1; half /= 2) {
      for (std::size_t i = half; i < n; i += 2 * half) Q[i] = midpoint(Q[i - half], Q[i + half]);
    }

    Eigen::VectorXd q = qa;
    const double dn = static_cast<double>(n);
    for (std::size_t i = 0; i < n; ++i) {
      if (Status s = step(static_cast<double>(i) / dn, Q[i], q, static_cast<double>(i + 1) / dn,
                          Q[i + 1], 0);
          !s) {
        return s;
      }
      q = points_.back();
    }
    // The walk ends on B's pose; it must end in B's joints too.
    const Eigen::VectorXd end = std::move(points_.back());
    points_.pop_back();
    int worst = 0;
    for (int j = 1; j < model_.dof(); ++j) {
      if (std::abs(end[j] - qb[j]) > std::abs(end[worst] - qb[worst])) worst = j;
    }
    if (std::abs(end[worst] - qb[worst]) > kCartesianEndTolerance) {
      return Error{where_ + " ends in another IK configuration than its target's: along the line " +
                   joint_label(model_, worst) + " arrives at " +
                   format_joint_value(model_, worst, end[worst]) + ", not at " +
                   format_joint_value(model_, worst, qb[worst]) +
                   "; give the waypoint the joints the line reaches, or move there in joint "
                   "space"};
    }
    return Status::Ok();
  }

  std::vector<Eigen::VectorXd>& points() { return points_; }

 private:
  Eigen::Vector3d position(double s) const {
    return {pa_[0] + s * (pb_[0] - pa_[0]), pa_[1] + s * (pb_[1] - pa_[1]),
            pa_[2] + s * (pb_[2] - pa_[2])};
  }

  Eigen::Isometry3d pose(double s, const Quat& Q) const {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = rotation_from_quat(Q);
    T.translation() = position(s);
    return T;
  }

  // "... at 41.4 % of its length (tool at [0.512, 0.100, 0.300] m)"
  std::string at(double s) const {
    const Eigen::Vector3d p = position(s);
    return where_ + " cannot be followed at " + percent(s) + " of its length (tool at [" +
           format_fixed(p[0], 3) + ", " + format_fixed(p[1], 3) + ", " + format_fixed(p[2], 3) +
           "] m): ";
  }

  Status too_many(std::size_t n) const {
    return Error{where_ + " needs " + std::to_string(n) + " points or more, more than the " +
                 std::to_string(budget_) + " the plan's maximum of waypoints leaves for it"};
  }

  // The IK solution on the joint grid, within the limits (rounding may cross one by a grid step).
  Eigen::VectorXd on_grid(const Eigen::VectorXd& q) const {
    Eigen::VectorXd out(q.size());
    for (Eigen::Index j = 0; j < q.size(); ++j) {
      const double rounded = std::nearbyint(q[j] / kCartesianJointGrid) * kCartesianJointGrid;
      out[j] = std::clamp(rounded, model_.lower_limits()[j], model_.upper_limits()[j]);
    }
    return out;
  }

  // From (s0, Q0, q0), a point already on the walk, to s1: appends the points up to s1.
  Status step(double s0, const Quat& Q0, const Eigen::VectorXd& q0, double s1, const Quat& Q1,
              int halvings) {
    auto ik = solve_ik_nearest(model_, pose(s1, Q1), q0);
    if (!ik) return Error{at(s1) + "the arm cannot reach the line there: " + ik.error().message};
    Eigen::VectorXd q1 = on_grid(ik->q);

    // The joint that moves most for its bound.
    int worst = 0;
    double worst_ratio = -1.0;
    for (int j = 0; j < model_.dof(); ++j) {
      const double bound = model_.joint(j).type == JointType::kPrismatic
                               ? kCartesianMaxJointStepM
                               : kCartesianMaxJointStepRad;
      const double ratio = std::abs(q1[j] - q0[j]) / bound;
      if (ratio > worst_ratio) {
        worst_ratio = ratio;
        worst = j;
      }
    }
    const double sm = 0.5 * (s0 + s1);
    const Quat Qm = midpoint(Q0, Q1);
    double chord_error_m = 0.0;
    bool chord_ok = true;
    if (worst_ratio <= 1.0) {
      // The joint-space chord's middle against the line's pose there.
      Eigen::VectorXd qm(model_.dof());
      for (int j = 0; j < model_.dof(); ++j) qm[j] = 0.5 * (q0[j] + q1[j]);
      forward_kinematics(model_, data_, qm);
      const Eigen::Vector3d p = data_.T_base_tool.translation();
      const Eigen::Vector3d line = position(sm);
      const double ex = p[0] - line[0], ey = p[1] - line[1], ez = p[2] - line[2];
      chord_error_m = std::sqrt(ex * ex + ey * ey + ez * ez);
      const double cos_half = std::abs(dot(quat_from_rotation(data_.T_base_tool.linear()), Qm));
      chord_ok = chord_error_m <= kCartesianChordToleranceM && cos_half >= kCosHalfChordTolerance;
      if (chord_ok) {
        if (points_.size() == budget_ + 1) return too_many(budget_ + 2);
        points_.push_back(std::move(q1));
        return Status::Ok();
      }
    }
    if (halvings == kCartesianMaxHalvings) {
      const std::string over = format_fixed(1000.0 * (s1 - s0) * length_, 4, "mm");
      if (worst_ratio > 1.0) {
        return Error{at(s1) + joint_label(model_, worst) + " jumps " +
                     format_joint_value(model_, worst, std::abs(q1[worst] - q0[worst])) + " over " +
                     over +
                     " of the line (a singularity, a joint limit in the way or another IK "
                     "configuration); split the segment or move there in joint space"};
      }
      return Error{at(s1) + "between IK solutions " + over +
                   " apart on the line the tool strays from it by " +
                   format_fixed(1000.0 * chord_error_m, 3, "mm") +
                   " or turns away from it (near a singularity); split the segment or move there "
                   "in joint space"};
    }
    if (Status s = step(s0, Q0, q0, sm, Qm, halvings + 1); !s) return s;
    const Eigen::VectorXd qm = points_.back();
    return step(sm, Qm, qm, s1, Q1, halvings + 1);
  }

  const RobotModel& model_;
  KinematicsData& data_;
  std::string where_;
  std::size_t budget_ = 0;
  Eigen::Vector3d pa_, pb_;
  double length_ = 0.0;
  std::vector<Eigen::VectorXd> points_;
};

// Lower bounds on the durations of the steps qa -> points[0] -> ... -> points.back() that
// ramp the speed up from rest at A and down to rest at B (the last step, into B, is left to
// the timing). The via-point timing alone would lengthen a long chain of short steps far
// more than needed (its blend repair was made for a few waypoints); this hands it durations
// whose blends already fit, except where the line's direction in joint space turns.
//
// Along the path, in units of "seconds at full speed" (sigma; step s is alpha_s long,
// alpha_s = max_j |D_sj| / v_j), a speed fraction r in (0, 1] gives joint j the velocity
// r D_sj / alpha_s; dr/dt = A then accelerates joint j at A |D_sj| / alpha_s, within a_j for
// A <= A_s = min_j a_j alpha_s / |D_sj|. With A half the smallest A_s (the other half left to
// the turns), r = min(1, sqrt(2 A sigma), sqrt(2 A (total - sigma))) at each step's middle,
// and the step lasts alpha_s / r. Only +, -, *, / and sqrt.
std::vector<double> ramp_durations(const RobotModel& model, const TrajectoryOptions& options,
                                   const Eigen::VectorXd& qa,
                                   const std::vector<Eigen::VectorXd>& points,
                                   const Eigen::VectorXd& qb) {
  const std::size_t n = points.size() + 1;  // steps
  auto from = [&](std::size_t s) -> const Eigen::VectorXd& { return s == 0 ? qa : points[s - 1]; };
  auto to = [&](std::size_t s) -> const Eigen::VectorXd& { return s + 1 == n ? qb : points[s]; };
  std::vector<double> alpha(n, 0.0);
  double A = std::numeric_limits<double>::infinity();
  for (std::size_t s = 0; s < n; ++s) {
    for (int j = 0; j < model.dof(); ++j) {
      const double v = options.velocity_scale * model.max_velocities()[j];
      alpha[s] = std::max(alpha[s], std::abs(to(s)[j] - from(s)[j]) / v);
    }
    for (int j = 0; j < model.dof(); ++j) {
      const double d = std::abs(to(s)[j] - from(s)[j]);
      if (d > 0.0) {
        const double a = options.acceleration_scale * model.max_accelerations()[j];
        A = std::min(A, a * alpha[s] / d);
      }
    }
  }
  std::vector<double> out(points.size(), 0.0);
  if (!(A < std::numeric_limits<double>::infinity())) return out;  // nothing moves
  A = 0.5 * A;
  double total = 0.0;
  for (const double a : alpha) total += a;
  double sigma = 0.0;
  for (std::size_t s = 0; s + 1 < n; ++s) {
    const double middle = sigma + 0.5 * alpha[s];
    sigma += alpha[s];
    const double r =
        std::min({1.0, std::sqrt(2.0 * A * middle), std::sqrt(2.0 * A * (total - middle))});
    if (r > 0.0) out[s] = alpha[s] / r;
  }
  return out;
}

}  // namespace

Result<std::vector<Eigen::VectorXd>> cartesian_segment_points(const RobotModel& model,
                                                              const Eigen::VectorXd& qa,
                                                              const Eigen::VectorXd& qb,
                                                              std::size_t index,
                                                              std::size_t max_points) {
  KinematicsData data(model);
  SegmentExpander expander(model, data,
                           "waypoint[" + std::to_string(index) +
                               "]: the Cartesian segment from waypoint[" +
                               std::to_string(index - 1) + "]");
  if (Status s = expander.expand(qa, qb, max_points); !s) return s.error();
  return std::move(expander.points());
}

bool has_cartesian_segments(const std::vector<JointWaypoint>& waypoints) {
  for (std::size_t k = 1; k < waypoints.size(); ++k) {
    if (waypoints[k].cartesian) return true;
  }
  return false;
}

double step_min_duration(const std::vector<JointWaypoint>& waypoints, std::size_t k) {
  const JointWaypoint& w = waypoints[k];
  if (!w.cartesian || w.expanded) return w.min_duration;
  std::size_t points = 0;  // the expanded points just before it
  while (points < k && waypoints[k - points - 1].expanded) ++points;
  return w.min_duration / static_cast<double>(points + 1);
}

std::vector<JointWaypoint> without_expanded_points(std::vector<JointWaypoint> waypoints) {
  std::erase_if(waypoints, [](const JointWaypoint& w) { return w.expanded; });
  return waypoints;
}

Result<std::vector<JointWaypoint>> expand_cartesian_segments(const RobotModel& model,
                                                             std::vector<JointWaypoint> waypoints,
                                                             const TrajectoryOptions& options) {
  waypoints = without_expanded_points(std::move(waypoints));
  if (!has_cartesian_segments(waypoints)) return waypoints;
  const auto max_total = static_cast<std::size_t>(std::max(options.max_waypoints, 1));
  std::vector<JointWaypoint> out;
  out.reserve(waypoints.size());
  for (std::size_t k = 0; k < waypoints.size(); ++k) {
    JointWaypoint& w = waypoints[k];
    if (k == 0 || !w.cartesian) {
      out.push_back(std::move(w));
      continue;
    }
    const std::size_t left = waypoints.size() - k;  // this one and those after it
    const std::size_t used = out.size() + left;
    const std::size_t budget = used < max_total ? max_total - used : 0;
    // A is out.back(): waypoints[k - 1] was moved there.
    auto points = cartesian_segment_points(model, out.back().q, w.q, k, budget);
    if (!points) return points.error();
    // B's min_duration spread evenly over the segment's steps (step_min_duration gives B's
    // share; B keeps the operator's value, which plan messages and hashes carry), and the
    // speed ramp's durations.
    const double min_duration = w.min_duration / static_cast<double>(points->size() + 1);
    const std::vector<double> ramp = ramp_durations(model, options, out.back().q, *points, w.q);
    for (std::size_t i = 0; i < points->size(); ++i) {
      JointWaypoint& point = out.emplace_back(std::move((*points)[i]),
                                              std::max(min_duration, ramp[i]), std::nullopt, true);
      point.expanded = true;
    }
    out.push_back(std::move(w));
  }
  return out;
}

}  // namespace telear::core
