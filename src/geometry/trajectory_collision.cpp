#include "telear/geometry/trajectory_collision.hpp"

#include <algorithm>
#include <cmath>
#include <map>

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

// The share of its interval a pair may be looked at early, with another pair that is due.
constexpr double kEarlyLook = 0.2;

struct PairState {
  double d_last = 0.0;  // lower bound on the distance at s_last (exact, early-stopped or cheap)
  double s_last = 0.0;  // where (segment parameter)
  double s_next = 0.0;  // where it must be looked at again (> 1: not on this segment)
  double speed = 0.0;   // motion bound per unit s on this segment
  double d_ref = 0.0;   // the last distance computed by FCL
  bool known = false;   // d_last holds (false before the first look and after a gripper change)
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
        state_(checker.pairs().size()),
        same_names_(group_by_names(checker)) {}

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
  double record_for(const CollisionPair& pair) const {
    return pair.other_body >= 0 ? report.min_clearance.distance_m
                                : report.min_workspace_clearance.distance_m;
  }

  // Per-pair advancement: after a look at s the pair is due again at s + ds / speed, where ds
  // of relative motion is the larger of
  //   - what its bound may lose before it falls below refresh_fraction of itself or below the
  //     smallest clearance so far (below either it must be looked at: it might set a new
  //     minimum), and
  //   - the conservative-advancement step min(max(d, resolution_m), max_step_m), which cannot
  //     miss a contact by more than resolution_m and samples a pair near the minimum clearance
  //     every max_step_m of motion.
  // Each pair keeps its own pace: a pair a few millimetres apart by design (a wrist's housings)
  // is looked at often, but no longer shortens every other pair's step.
  void schedule(std::size_t p, double s) {
    PairState& st = state_[p];
    if (!(st.speed > 0.0)) {
      st.s_next = 2.0;  // nothing moves one against the other on this segment
      return;
    }
    double ds = 0.0;
    if (st.in_contact) {
      ds = options_.contact_step_m;
    } else {
      const double d = st.d_last;
      const double keep =
          d - std::max(options_.refresh_fraction * d, record_for(checker_.pairs()[p]));
      ds = std::max(keep, std::min(std::max(d, options_.resolution_m), options_.max_step_m));
    }
    st.s_next = s + ds / st.speed;
  }

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
    const double fraction = trajectory_.gripper_at(t0).value_or(options_.initial_gripper_fraction);
    // The fingers move with the gripper between segments: every bound is re-established then.
    if (fraction != fraction_) {
      for (PairState& st : state_) st.known = false;
      fraction_ = fraction;
    }
    for (std::size_t p = 0; p < pairs.size(); ++p) {
      PairState& st = state_[p];
      // A bound carried over from the previous segment (its end is this one's start): what it
      // may have lost since its last look; then looked at now, or scheduled from it.
      if (st.known && !st.in_contact) {
        st.d_last = std::max(0.0, st.d_last - (1.0 - st.s_last) * st.speed);
      }
      st.s_last = 0.0;
      st.speed = pairs[p].other_body >= 0
                     ? relative_speed(robot, D, static_cast<std::size_t>(pairs[p].body),
                                      static_cast<std::size_t>(pairs[p].other_body))
                     : body_speed[static_cast<std::size_t>(pairs[p].body)];
      const bool due =
          !st.known || st.in_contact ||
          st.d_last < std::max(options_.refresh_fraction * st.d_ref, record_for(pairs[p])) ||
          profile == nullptr;
      if (due) {
        st.s_next = 0.0;
      } else {
        schedule(p, 0.0);
      }
    }
    auto time_of = [&](double s) { return profile ? t0 + time_at(*profile, s) : t0; };

    while (true) {
      double s = 2.0;
      for (const PairState& st : state_) s = std::min(s, st.s_next);
      if (s > 1.0) break;
      if (++report.evaluations > options_.max_evaluations) {
        return Error{"collision check: more than " + std::to_string(options_.max_evaluations) +
                     " configurations on segment " + std::to_string(segment_) +
                     " (raise max_evaluations or the resolution)"};
      }
      checker_.set_configuration(q0 + D * s, fraction);
      // Only the pairs due are looked at (the checker poses only their bodies), with those
      // that have used most of their interval: looking early is safe, and one configuration
      // then serves several pairs instead of one each.
      for (std::size_t p = 0; p < pairs.size(); ++p) {
        const PairState& st = state_[p];
        if (st.s_next > s && st.s_next - s > kEarlyLook * (st.s_next - st.s_last)) continue;
        update_pair(p, s, time_of);
        schedule(p, s);
      }
    }
    return Status::Ok();
  }

  template <typename TimeOf>
  void update_pair(std::size_t p, double s, const TimeOf& time_of) {
    const CollisionPair& pair = checker_.pairs()[p];
    PairState& st = state_[p];
    st.s_last = s;
    st.known = true;
    // The bounds' distance first (no FCL query): enough while it stays above the smallest
    // clearance so far (the pair cannot set a new minimum) and above refresh_fraction of the
    // last exact distance (so that the step it allows stays long). Not in contact then.
    if (!st.in_contact) {
      const double cheap = checker_.distance_lower_bound(pair);
      if (cheap > record_for(pair) && cheap >= options_.refresh_fraction * st.d_ref) {
        st.d_last = cheap;
        return;
      }
    }
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
    const bool contact = d.distance_m <= 0.0 && checker_.in_contact(pair);
    st.d_last = std::max(d.lower_bound_m, 0.0);
    st.d_ref = st.d_last;
    const std::string& body = checker_.robot().bodies[static_cast<std::size_t>(pair.body)].name;
    if (contact) {
      const double depth = checker_.penetration_depth(pair);
      if (!st.in_contact) {
        st.in_contact = true;
        // A link split into parts (convex_hull.hpp) touches with several pairs: one episode
        // per link pair while any of them is in contact.
        const std::size_t open = open_episode(p);
        if (open != kNone) {
          st.episode = open;
          report.collisions[open].depth_m = std::max(report.collisions[open].depth_m, depth);
        } else {
          st.episode = report.collisions.size();
          report.collisions.push_back({time_of(s), body, checker_.pair_other_name(pair),
                                       pair.other_body >= 0, depth, segment_});
        }
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

  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);

  // The episode of another pair of the same two names still in contact, or kNone.
  std::size_t open_episode(std::size_t p) const {
    for (std::size_t q : same_names_[p]) {
      if (q != p && state_[q].in_contact) return state_[q].episode;
    }
    return kNone;
  }

  // Per pair, the pairs of the same body and other names (itself included).
  static std::vector<std::vector<std::size_t>> group_by_names(const CollisionChecker& checker) {
    const std::vector<CollisionPair>& pairs = checker.pairs();
    std::map<std::pair<std::string, std::string>, std::vector<std::size_t>> groups;
    std::vector<const std::vector<std::size_t>*> group_of(pairs.size());
    for (std::size_t p = 0; p < pairs.size(); ++p) {
      const CollisionPair& pair = pairs[p];
      groups[{checker.robot().bodies[static_cast<std::size_t>(pair.body)].name,
              (pair.other_body >= 0 ? "body:" : "object:") + checker.pair_other_name(pair)}]
          .push_back(p);
    }
    std::vector<std::vector<std::size_t>> out(pairs.size());
    for (const auto& [names, members] : groups) {
      for (std::size_t p : members) out[p] = members;
    }
    return out;
  }

  CollisionChecker& checker_;
  const core::Trajectory& trajectory_;
  const TrajectoryCheckOptions& options_;
  std::vector<PairState> state_;
  std::vector<std::vector<std::size_t>> same_names_;
  double fraction_ = -1.0;  // the gripper fraction the bounds hold for
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
