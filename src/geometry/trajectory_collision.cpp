#include "telear/geometry/trajectory_collision.hpp"

#include <algorithm>
#include <cmath>

#include "telear/core/number_format.hpp"

namespace telear::geometry {
namespace {

// The time within a segment's profile at which s reaches `target` (s(t) is monotonic).
double time_at(const core::TrapezoidalProfile& profile, double target) {
  if (target <= 0.0) return 0.0;
  if (target >= 1.0) return profile.duration;
  double lo = 0.0, hi = profile.duration;
  for (int i = 0; i < 60 && hi - lo > 1e-9; ++i) {
    const double mid = 0.5 * (lo + hi);
    double s = 0.0, sd = 0.0, sdd = 0.0;
    profile.sample(mid, s, sd, sdd);
    (s < target ? lo : hi) = mid;
  }
  return hi;
}

// Motion bound per unit s of body b relative to body a (the distance between two bodies does
// not change when both move rigidly together): only the joints between the inner body's frame
// and the outer one's move one against the other, so the outer body's levers about those joints
// bound it.
double relative_speed(const RobotCollisionModel& robot, const Eigen::VectorXd& D, std::size_t a,
                      std::size_t b) {
  if (robot.bodies[a].frame > robot.bodies[b].frame) std::swap(a, b);
  double speed = 0.0;
  for (std::size_t j = static_cast<std::size_t>(robot.bodies[a].frame); j < robot.lever.size();
       ++j) {
    speed += std::abs(D[static_cast<Eigen::Index>(j)]) * robot.lever[j][b];
  }
  return speed;
}

struct PairState {
  double d_last = 0.0;  // distance when last computed
  double s_last = 0.0;  // where (segment parameter)
  double speed = 0.0;   // motion bound per unit s on this segment
  bool in_contact = false;
  std::size_t episode = 0;  // index into the collisions while in contact
};

class Walker {
 public:
  Walker(CollisionChecker& checker, const core::Trajectory& trajectory,
         const TrajectoryCheckOptions& options)
      : checker_(checker),
        trajectory_(trajectory),
        options_(options),
        state_(checker.pairs().size()) {}

  Status run() {
    const auto& waypoints = trajectory_.waypoints();
    const auto& times = trajectory_.waypoint_times();
    const auto& profiles = trajectory_.segment_profiles();
    if (waypoints.size() == 1) {
      segment_ = 0;
      return walk(waypoints[0].q, waypoints[0].q, nullptr, times[0]);
    }
    for (std::size_t k = 0; k + 1 < waypoints.size(); ++k) {
      segment_ = static_cast<int>(k);
      if (Status s = walk(waypoints[k].q, waypoints[k + 1].q, &profiles[k], times[k]); !s) {
        return s;
      }
    }
    return Status::Ok();
  }

  TrajectoryCheckReport report;

 private:
  // One segment from q0 (s = 0) to q1 (s = 1) starting at time t0.
  Status walk(const Eigen::VectorXd& q0, const Eigen::VectorXd& q1,
              const core::TrapezoidalProfile* profile, double t0) {
    const RobotCollisionModel& robot = checker_.robot();
    const std::vector<CollisionPair>& pairs = checker_.pairs();
    const Eigen::VectorXd D = q1 - q0;
    // Motion bound of each body per unit s.
    std::vector<double> body_speed(robot.bodies.size(), 0.0);
    for (std::size_t b = 0; b < robot.bodies.size(); ++b) {
      for (std::size_t j = 0; j < robot.lever.size(); ++j) {
        body_speed[b] += std::abs(D[static_cast<Eigen::Index>(j)]) * robot.lever[j][b];
      }
    }
    for (std::size_t p = 0; p < pairs.size(); ++p) {
      state_[p].speed = pairs[p].other_body >= 0
                            ? relative_speed(robot, D, static_cast<std::size_t>(pairs[p].body),
                                             static_cast<std::size_t>(pairs[p].other_body))
                            : body_speed[static_cast<std::size_t>(pairs[p].body)];
    }
    const double fastest =
        body_speed.empty() ? 0.0 : *std::max_element(body_speed.begin(), body_speed.end());
    const double fraction = trajectory_.gripper_at(t0).value_or(options_.initial_gripper_fraction);
    auto time_of = [&](double s) { return profile ? t0 + time_at(*profile, s) : t0; };

    double s = 0.0;
    Eigen::VectorXd q = q0;
    bool first = true;
    while (true) {
      if (++report.evaluations > options_.max_evaluations) {
        return Error{"collision check: more than " + std::to_string(options_.max_evaluations) +
                     " configurations on segment " + std::to_string(segment_) +
                     " (raise max_evaluations or the resolution)"};
      }
      q = q0 + D * s;
      checker_.set_configuration(q, fraction);
      double step = fastest > 0.0 ? options_.max_step_m / fastest : 1.0;
      for (std::size_t p = 0; p < pairs.size(); ++p) {
        PairState& st = state_[p];
        double bound = first ? 0.0 : st.d_last - (s - st.s_last) * st.speed;
        // Re-computed when its bound has shrunk, or when it could set a new minimum clearance
        // (so that the minimum is sampled every step, not every refresh).
        const double record = pairs[p].other_body >= 0 ? report.min_clearance.distance_m
                                                       : report.min_workspace_clearance.distance_m;
        if (first || st.in_contact || bound < options_.refresh_fraction * st.d_last ||
            bound < record) {
          update_pair(p, s, time_of);
          bound = st.in_contact ? 0.0 : st.d_last;
        }
        if (st.speed > 0.0) {
          const double floor = st.in_contact ? options_.contact_step_m : options_.resolution_m;
          step = std::min(step, std::max(bound, floor) / st.speed);
        }
      }
      first = false;
      if (s >= 1.0) break;
      s = std::min(1.0, s + step);
    }
    return Status::Ok();
  }

  template <typename TimeOf>
  void update_pair(std::size_t p, double s, const TimeOf& time_of) {
    const CollisionPair& pair = checker_.pairs()[p];
    PairState& st = state_[p];
    // A quick bound first (meshes: an early-stopped search); exact only where the pair might
    // set a new minimum clearance.
    PairDistance d = checker_.distance(pair, options_.relative_error);
    ++report.distance_queries;
    const double record = pair.other_body >= 0 ? report.min_clearance.distance_m
                                               : report.min_workspace_clearance.distance_m;
    if (d.distance_m > 0.0 && d.lower_bound_m < d.distance_m && d.lower_bound_m < record) {
      d = checker_.distance(pair, 0.0);
      ++report.distance_queries;
    }
    st.s_last = s;
    const bool contact = d.distance_m <= 0.0 && checker_.in_contact(pair);
    st.d_last = std::max(d.lower_bound_m, 0.0);
    const std::string& body = checker_.robot().bodies[static_cast<std::size_t>(pair.body)].name;
    if (contact) {
      const double depth = checker_.penetration_depth(pair);
      if (!st.in_contact) {
        st.in_contact = true;
        st.episode = report.collisions.size();
        report.collisions.push_back({time_of(s), body, checker_.pair_other_name(pair),
                                     pair.other_body >= 0, depth, segment_});
      } else {
        PlanCollision& c = report.collisions[st.episode];
        c.depth_m = std::max(c.depth_m, depth);
      }
    } else {
      st.in_contact = false;
    }
    const bool self = pair.other_body >= 0;
    if (st.d_last < report.min_clearance.distance_m) {
      report.min_clearance = {st.d_last, time_of(s), segment_, body, checker_.pair_other_name(pair),
                              self};
    }
    if (!self && st.d_last < report.min_workspace_clearance.distance_m) {
      report.min_workspace_clearance = {
          st.d_last, time_of(s), segment_, body, checker_.pair_other_name(pair), false};
    }
  }

  CollisionChecker& checker_;
  const core::Trajectory& trajectory_;
  const TrajectoryCheckOptions& options_;
  std::vector<PairState> state_;
  int segment_ = 0;
};

}  // namespace

Status TrajectoryCheckOptions::validate() const {
  auto positive = [](double v, const char* name) -> Status {
    if (!(v > 0.0) || !std::isfinite(v)) {
      return Error{std::string(name) + " must be a positive number, got " + core::format_number(v)};
    }
    return Status::Ok();
  };
  if (Status s = positive(resolution_m, "resolution_m"); !s) return s;
  if (Status s = positive(contact_step_m, "contact_step_m"); !s) return s;
  if (Status s = positive(max_step_m, "max_step_m"); !s) return s;
  if (!(refresh_fraction > 0.0 && refresh_fraction < 1.0)) {
    return Error{"refresh_fraction must lie in (0, 1), got " +
                 core::format_number(refresh_fraction)};
  }
  if (!(initial_gripper_fraction >= 0.0 && initial_gripper_fraction <= 1.0)) {
    return Error{"initial_gripper_fraction must lie in [0, 1], got " +
                 core::format_number(initial_gripper_fraction)};
  }
  if (max_evaluations < 1) return Error{"max_evaluations must be at least 1"};
  if (!(relative_error >= 0.0) || !std::isfinite(relative_error)) {
    return Error{"relative_error must be a finite number >= 0, got " +
                 core::format_number(relative_error)};
  }
  return Status::Ok();
}

Result<TrajectoryCheckReport> check_trajectory(CollisionChecker& checker,
                                               const core::Trajectory& trajectory,
                                               const TrajectoryCheckOptions& options) {
  if (Status s = options.validate(); !s) return Error{"collision check: " + s.error().message};
  if (trajectory.dof() != checker.robot().model->dof()) {
    return Error{"collision check: the trajectory has " + std::to_string(trajectory.dof()) +
                 " joints, the robot " + std::to_string(checker.robot().model->dof())};
  }
  Walker walker(checker, trajectory, options);
  if (Status s = walker.run(); !s) return s.error();
  return std::move(walker.report);
}

TrajectoryCheckReport check_trajectory_sampled(CollisionChecker& checker,
                                               const core::Trajectory& trajectory, double dt_s,
                                               double initial_gripper_fraction) {
  TrajectoryCheckReport report;
  const std::vector<CollisionPair>& pairs = checker.pairs();
  std::vector<bool> in_contact(pairs.size(), false);
  Eigen::VectorXd q;
  const double duration = trajectory.duration();
  const long steps = std::max(1L, static_cast<long>(std::ceil(duration / dt_s)));
  for (long i = 0; i <= steps; ++i) {
    const double t = std::min(duration, static_cast<double>(i) * dt_s);
    trajectory.sample(t, q);
    checker.set_configuration(q, trajectory.gripper_at(t).value_or(initial_gripper_fraction));
    ++report.evaluations;
    for (std::size_t p = 0; p < pairs.size(); ++p) {
      const PairDistance d = checker.distance(pairs[p]);
      ++report.distance_queries;
      const std::string& body =
          checker.robot().bodies[static_cast<std::size_t>(pairs[p].body)].name;
      const bool contact = d.distance_m <= 0.0 && checker.in_contact(pairs[p]);
      if (contact && !in_contact[p]) {
        report.collisions.push_back({t, body, checker.pair_other_name(pairs[p]),
                                     pairs[p].other_body >= 0, checker.penetration_depth(pairs[p]),
                                     0});
      }
      in_contact[p] = contact;
      const double clearance = std::max(d.distance_m, 0.0);
      const bool self = pairs[p].other_body >= 0;
      if (clearance < report.min_clearance.distance_m) {
        report.min_clearance = {clearance, t, 0, body, checker.pair_other_name(pairs[p]), self};
      }
      if (!self && clearance < report.min_workspace_clearance.distance_m) {
        report.min_workspace_clearance = {clearance, t, 0, body, checker.pair_other_name(pairs[p]),
                                          false};
      }
    }
  }
  return report;
}

}  // namespace telear::geometry
