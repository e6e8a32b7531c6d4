#include "telear/core/ik_branches.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "telear/core/angles.hpp"
#include "telear/core/ik_numeric.hpp"
#include "telear/core/ik_ur.hpp"
#include "telear/core/joint_limits.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/motion_command.hpp"
#include "telear/core/number_format.hpp"
#include "telear/core/seeded_random.hpp"

namespace telear::core {
namespace {

// The model with every revolute joint turning freely in [-pi, pi] (a span of 2 pi: the
// numeric solver wraps such joints instead of holding them at a limit).
Result<RobotModel> free_model(const RobotModel& model) {
  RobotModel::Description d;
  d.name = model.name();
  d.source = model.source();
  d.joints = model.joints();
  d.T_flange_tool = model.T_flange_tool();
  d.dh = model.dh();
  for (Joint& joint : d.joints) {
    if (joint.type != JointType::kRevolute) continue;
    joint.limits.lower = -std::numbers::pi;
    joint.limits.upper = std::numbers::pi;
  }
  return RobotModel::create(std::move(d));
}

bool same_branch(const RobotModel& model, const Eigen::VectorXd& a, const Eigen::VectorXd& b,
                 double tolerance) {
  for (int j = 0; j < model.dof(); ++j) {
    const double d =
        model.joint(j).type == JointType::kRevolute ? wrap_to_pi(a[j] - b[j]) : a[j] - b[j];
    if (std::abs(d) > tolerance) return false;
  }
  return true;
}

Status positive(const char* field, double value) {
  if (value > 0.0 && std::isfinite(value)) return Status::Ok();
  return Error{std::string("IkBranchOptions::") + field + " must be positive and finite, got " +
               format_number(value)};
}

// Moves each revolute joint of q (wrapped to (-pi, pi]) to its 2 pi equivalent within the
// limits nearest zero: the wrapped value when it is inside, else the lowest or highest inside
// equivalent, whichever is nearer zero. False when some joint has none.
bool move_into_limits(const RobotModel& model, Eigen::VectorXd& q) {
  bool inside = true;
  for (int j = 0; j < model.dof(); ++j) {
    const double lo = model.lower_limits()[j], hi = model.upper_limits()[j];
    if (model.joint(j).type != JointType::kRevolute) {
      inside = inside && q[j] >= lo && q[j] <= hi;
      continue;
    }
    if (q[j] >= lo && q[j] <= hi) continue;
    const auto low = angle_equivalent_within(q[j], lo, hi);
    if (!low) {
      inside = false;
      continue;
    }
    double best = *low;
    for (double v = *low; v <= hi; v += 2.0 * std::numbers::pi) {
      if (std::abs(v) < std::abs(best)) best = v;
    }
    q[j] = best;
  }
  return inside;
}

Status check_input(const RobotModel& model, const Eigen::Isometry3d& T_base_tool,
                   const IkBranchOptions& options) {
  if (Status s = check_ik_branch_options(options); !s) return s;
  if (!T_base_tool.matrix().allFinite()) return Error{"solve_ik_all: target pose is not finite"};
  if (model.dof() > 6) {
    return Error{"solve_ik_all: " + model.name() + " has " + std::to_string(model.dof()) +
                 " joints, so a reachable pose has a continuum of solutions, not branches; use "
                 "solve_ik_nearest (null-space preference)"};
  }
  return Status::Ok();
}

// The closed form's solutions as a listing: those repeating an earlier one (within the
// distinct tolerance: they meet at singularities) dropped, joints moved into the limits.
Result<std::vector<IkSolution>> closed_form_listing(const RobotModel& model, AnalyticIkResult all,
                                                    const IkBranchOptions& options) {
  if (all.status == IkStatus::kUnreachable) return Error{"solve_ik_all: " + all.message};
  std::vector<IkSolution> out;
  out.reserve(all.solutions.size());
  for (IkSolution& s : all.solutions) {
    const bool repeat = std::any_of(out.begin(), out.end(), [&](const IkSolution& b) {
      return same_branch(model, b.q, s.q, options.distinct_tolerance_rad);
    });
    if (repeat) continue;
    s.within_limits = move_into_limits(model, s.q);
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace

Status check_ik_branch_options(const IkBranchOptions& o) {
  if (o.attempts <= 0) {
    return Error{"IkBranchOptions::attempts must be positive, got " + std::to_string(o.attempts)};
  }
  if (o.max_branches <= 0) {
    return Error{"IkBranchOptions::max_branches must be positive, got " +
                 std::to_string(o.max_branches)};
  }
  if (o.max_iterations <= 0) {
    return Error{"IkBranchOptions::max_iterations must be positive, got " +
                 std::to_string(o.max_iterations)};
  }
  for (const auto& [field, value] :
       {std::pair{"position_tolerance_m", o.position_tolerance_m},
        std::pair{"orientation_tolerance_rad", o.orientation_tolerance_rad},
        std::pair{"distinct_tolerance_rad", o.distinct_tolerance_rad},
        std::pair{"singular_threshold", o.singular_threshold}}) {
    if (Status s = positive(field, value); !s) return s;
  }
  return Status::Ok();
}

Result<std::vector<IkSolution>> search_ik_branches(const RobotModel& model,
                                                   const Eigen::Isometry3d& T_base_tool,
                                                   const IkBranchOptions& options) {
  if (Status s = check_input(model, T_base_tool, options); !s) return s.error();
  auto free = free_model(model);
  if (!free) return free.error();
  NumericIkOptions lm;
  lm.max_iterations = options.max_iterations;
  lm.max_restarts = 0;
  lm.position_tolerance_m = options.position_tolerance_m;
  lm.orientation_tolerance_rad = options.orientation_tolerance_rad;
  NumericIkSolver solver(*free, lm);

  const int n = model.dof();
  std::uint64_t state = options.seed;
  Eigen::VectorXd seed(n);
  std::vector<Eigen::VectorXd> found;
  double closest_m = std::numeric_limits<double>::infinity();
  double closest_rad = std::numeric_limits<double>::infinity();
  for (int attempt = 0;
       attempt < options.attempts && static_cast<int>(found.size()) < options.max_branches;
       ++attempt) {
    for (int j = 0; j < n; ++j) {
      const double lo = free->lower_limits()[j], hi = free->upper_limits()[j];
      const bool finite = std::isfinite(lo) && std::isfinite(hi);
      const double u = uniform01(state);
      seed[j] = finite ? lo + (hi - lo) * u : -std::numbers::pi + 2.0 * std::numbers::pi * u;
    }
    const NumericIkResult r = solver.solve(T_base_tool, seed);
    if (!r.success) {
      if (r.position_error_m + r.orientation_error_rad < closest_m + closest_rad) {
        closest_m = r.position_error_m;
        closest_rad = r.orientation_error_rad;
      }
      continue;
    }
    Eigen::VectorXd q = r.q;
    for (int j = 0; j < n; ++j) {
      if (model.joint(j).type == JointType::kRevolute) q[j] = wrap_to_pi(q[j]);
    }
    const bool known = std::any_of(found.begin(), found.end(), [&](const Eigen::VectorXd& b) {
      return same_branch(model, b, q, options.distinct_tolerance_rad);
    });
    if (!known) found.push_back(std::move(q));
  }
  if (found.empty()) {
    return Error{"solve_ik_all: target unreachable: none of " + std::to_string(options.attempts) +
                 " seeded attempts converged; the closest came within " +
                 format_number(closest_m, "%.3g") + " m and " + format_number(closest_rad, "%.3g") +
                 " rad"};
  }
  // A stable order: lexicographic on the wrapped joint values, values within the distinct
  // tolerance counting as equal (branches share joints: the UR's four branches of one
  // shoulder have the same q1 up to rounding, which must not decide their order).
  const double tie = options.distinct_tolerance_rad;
  std::sort(found.begin(), found.end(), [tie](const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
    for (Eigen::Index j = 0; j < a.size(); ++j) {
      if (std::abs(a[j] - b[j]) > tie) return a[j] < b[j];
    }
    return false;
  });
  std::vector<IkSolution> out;
  out.reserve(found.size());
  KinematicsData data(model);
  for (size_t i = 0; i < found.size(); ++i) {
    IkSolution s;
    // Appended, not "b" + to_string(i): GCC 12 warns falsely (-Wrestrict) on the latter.
    s.config = "b";
    s.config += std::to_string(i);
    s.q = found[i];
    s.within_limits = move_into_limits(model, s.q);
    s.singular = jacobian_min_singular_value(model, data, s.q) < options.singular_threshold;
    out.push_back(std::move(s));
  }
  return out;
}

Result<std::vector<IkSolution>> solve_ik_all(const RobotModel& model,
                                             const Eigen::Isometry3d& T_base_tool,
                                             const IkBranchOptions& options) {
  if (Status s = check_input(model, T_base_tool, options); !s) return s.error();
  if (model.dof() == 6) {
    if (auto puma = puma_geometry(model)) {
      return closed_form_listing(model, solve_analytic_ik(model, *puma, T_base_tool), options);
    }
    if (auto ur = ur_geometry(model)) {
      return closed_form_listing(model, solve_ur_analytic_ik(model, *ur, T_base_tool), options);
    }
  }
  return search_ik_branches(model, T_base_tool, options);
}

}  // namespace telear::core
