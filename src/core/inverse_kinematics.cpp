#include "telear/core/inverse_kinematics.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>

#include "telear/core/ik_numeric.hpp"
#include "telear/core/ik_ur.hpp"
#include "telear/core/joint_limits.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/pose.hpp"

#include "ik_common.hpp"

namespace telear::core {
namespace {

// Exact wrist singularity of the closed form (its ZYZ decomposition set q4 = 0).
constexpr double kWristDegenerate = 1e-13;
// Numeric solutions: smallest Jacobian singular value below this is reported as singular.
constexpr double kJacobianSingular = 1e-6;
constexpr double kPreciseTolerance = 1e-9;  // m and rad

// Moves each revolute joint of q to the 2*pi-equivalent nearest q_current within the limits.
// Returns false when some joint has no equivalent within its limits (q then holds the
// equivalents nearest q_current, for the message).
bool nearest_equivalent_within_limits(const RobotModel& model, const Eigen::VectorXd& q_current,
                                      Eigen::VectorXd& q) {
  bool inside = true;
  for (int j = 0; j < model.dof(); ++j) {
    const double lower = model.lower_limits()[j];
    const double upper = model.upper_limits()[j];
    if (model.joint(j).type != JointType::kRevolute) {
      if (q[j] < lower - kLimitTolerance || q[j] > upper + kLimitTolerance) inside = false;
      continue;
    }
    const double nearest = std::round((q_current[j] - q[j]) / (2.0 * std::numbers::pi));
    // Doubles, so that infinite limits give infinite bounds on k.
    const double k_min = std::ceil((lower - kLimitTolerance - q[j]) / (2.0 * std::numbers::pi));
    const double k_max = std::floor((upper + kLimitTolerance - q[j]) / (2.0 * std::numbers::pi));
    if (k_min > k_max) {
      inside = false;
      q[j] += 2.0 * std::numbers::pi * nearest;
      continue;
    }
    q[j] += 2.0 * std::numbers::pi * std::clamp(nearest, k_min, k_max);
    q[j] = std::clamp(q[j], lower, upper);  // absorb the tolerance
  }
  return inside;
}

// The nearest in-limit solution of a closed form's. `puma` is given for the PUMA's, whose
// exact wrist singularity sets q4 = 0 (moved to q_current here); the UR class's solver was
// given q_current for the joints a singularity leaves free.
Result<IkSolution> nearest_analytic(const RobotModel& model, AnalyticIkResult all,
                                    const Eigen::VectorXd& q_current, const PumaGeometry* puma) {
  if (all.status == IkStatus::kUnreachable) return Error{all.message};
  double best_distance = std::numeric_limits<double>::infinity();
  int best = -1;
  double closest_outside_distance = std::numeric_limits<double>::infinity();
  IkSolution closest_outside;
  for (size_t i = 0; i < all.solutions.size(); ++i) {
    IkSolution& s = all.solutions[i];
    Eigen::VectorXd q = s.q;
    const double theta5 =
        puma != nullptr ? (puma->mirrored ? -1.0 : 1.0) * (q[4] + puma->offset[4]) : 1.0;
    if (puma != nullptr && s.singular && std::abs(std::sin(theta5)) < kWristDegenerate) {
      // Only q4 + q6 (cos theta5 > 0) or q4 - q6 is determined: keep q4 where it is.
      const double shift = q_current[3] - q[3];
      q[3] += shift;
      q[5] += std::cos(theta5) > 0.0 ? -shift : shift;
      Eigen::VectorXd q_shifted = q;
      if (!nearest_equivalent_within_limits(model, q_current, q_shifted)) q = s.q;
    }
    const bool inside = nearest_equivalent_within_limits(model, q_current, q);
    const double distance = (q - q_current).squaredNorm();
    s.q = q;
    s.within_limits = inside;
    if (inside && distance < best_distance) {
      best_distance = distance;
      best = static_cast<int>(i);
    }
    if (!inside && distance < closest_outside_distance) {
      closest_outside_distance = distance;
      closest_outside = s;
    }
  }
  if (best < 0) {
    std::string why = "no IK solution within the joint limits";
    if (closest_outside.q.size() != 0) {
      if (auto v = first_limit_violation(model, closest_outside.q, kLimitTolerance)) {
        why += ": in the nearest one (" + closest_outside.config + ") " +
               describe_violation(model, *v);
      }
    }
    return Error{why};
  }
  return std::move(all.solutions[static_cast<size_t>(best)]);
}

Result<IkSolution> nearest_numeric(const RobotModel& model, const Eigen::Isometry3d& T_base_tool,
                                   const Eigen::VectorXd& q_current,
                                   const RedundancyOptions& redundancy) {
  // Motion commands want the pose exactly: ask for 1e-9 first, and settle for the solver's
  // default 1e-6 only where that fails (near singular targets, where convergence is slow).
  NumericIkOptions precise;
  precise.position_tolerance_m = kPreciseTolerance;
  precise.orientation_tolerance_rad = kPreciseTolerance;
  precise.max_restarts = 20;
  const bool redundant = model.dof() > 6;
  KinematicsData data(model);
  auto reaches_precisely = [&](const Eigen::VectorXd& q) {
    forward_kinematics(model, data, q);
    const Vector6d e = pose_error_in_base(data.T_base_tool, T_base_tool);
    return e.head<3>().norm() <= kPreciseTolerance && e.tail<3>().norm() <= kPreciseTolerance;
  };
  // A redundant arm's null-space search restores the pose to its pose_tolerance (1e-10) by
  // Newton steps of its own, so LM need only find the self-motion, at its default 1e-6: the
  // last LM iterations, and the slow convergence at 1e-9 near singular targets, are saved.
  // Where that restoring fails, the precise route below runs after all.
  for (const bool coarse : {true, false}) {
    if (coarse && !redundant) continue;
    NumericIkResult r =
        NumericIkSolver(model, coarse ? NumericIkOptions{} : precise).solve(T_base_tool, q_current);
    if (!r.success && !coarse) r = NumericIkSolver(model).solve(T_base_tool, q_current);
    if (!r.success) return Error{"target unreachable (numeric IK): " + r.message};
    IkSolution s;
    s.config = "numeric";
    s.q = r.q;
    s.within_limits = nearest_equivalent_within_limits(model, q_current, s.q);
    if (redundant && s.within_limits) {
      const Eigen::VectorXd& preferred =
          redundancy.preference == NullSpacePreference::kRest ? redundancy.rest_q : q_current;
      s.q = optimize_null_space(model, T_base_tool, s.q, preferred, redundancy).q;
      s.config = "redundant";
    }
    if (coarse && !reaches_precisely(s.q)) continue;
    forward_kinematics(model, data, s.q);
    Jacobian J;
    geometric_jacobian(model, data, JacobianFrame::kBase, J);
    // Smallest singular value of J: square root of the smallest eigenvalue of the smaller Gram
    // matrix (J J^T for 6 or more joints; J^T J padded with an identity block otherwise, whose
    // eigenvalues of 1 are far above the threshold).
    Eigen::Matrix<double, 6, 6> gram = Eigen::Matrix<double, 6, 6>::Identity();
    if (model.dof() >= 6) {
      gram.noalias() = J * J.transpose();
    } else {
      gram.topLeftCorner(model.dof(), model.dof()).noalias() = J.transpose() * J;
    }
    // Eigenvalues only (ascending), cheaper than an SVD of the symmetric Gram matrix.
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eigen(gram,
                                                                           Eigen::EigenvaluesOnly);
    s.singular = std::sqrt(std::max(0.0, eigen.eigenvalues()[0])) < kJacobianSingular;
    return s;
  }
  return Error{"target unreachable (numeric IK)"};  // not reached: the precise pass returns
}

}  // namespace

Result<IkSolution> solve_ik_nearest(const RobotModel& model, const Eigen::Isometry3d& T_base_tool,
                                    const Eigen::VectorXd& q_current) {
  return solve_ik_nearest(model, T_base_tool, q_current, RedundancyOptions{});
}

Result<IkSolution> solve_ik_nearest(const RobotModel& model, const Eigen::Isometry3d& T_base_tool,
                                    const Eigen::VectorXd& q_current,
                                    const RedundancyOptions& redundancy) {
  if (Status s = check_redundancy_options(model, redundancy); !s) return s.error();
  assert(q_current.size() == model.dof() && "solve_ik_nearest(): wrong joint vector size");
  if (!T_base_tool.matrix().allFinite()) return Error{"target pose is not finite"};
  if (auto geometry = puma_geometry(model)) {
    return nearest_analytic(model, solve_analytic_ik(model, *geometry, T_base_tool), q_current,
                            &*geometry);
  }
  if (model.dof() == 6) {
    if (auto geometry = ur_geometry(model)) {
      const Vector6d q_free = q_current;
      return nearest_analytic(model,
                              solve_ur_analytic_ik(model, *geometry, T_base_tool, "", q_free),
                              q_current, nullptr);
    }
  }
  return nearest_numeric(model, T_base_tool, q_current, redundancy);
}

}  // namespace telear::core
