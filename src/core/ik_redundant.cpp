#include "telear/core/ik_redundant.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "telear/core/kinematics.hpp"
#include "telear/core/number_format.hpp"
#include "telear/core/pose.hpp"

namespace telear::core {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr int kCorrections = 8;         // Newton steps restoring the pose after a step
constexpr int kHalvings = 30;           // of alpha, before giving up on a direction
constexpr double kGramDamping = 1e-12;  // keeps J J^T invertible at a singularity

// The penalty acts on joint i when its limits are finite and span less than a full turn.
bool penalized(const RobotModel& model, int i) {
  const double lo = model.lower_limits()[i], hi = model.upper_limits()[i];
  return std::isfinite(lo) && std::isfinite(hi) &&
         !(model.joint(i).type == JointType::kRevolute && hi - lo >= kTwoPi) && hi > lo;
}

bool inside(const RobotModel& model, const Eigen::VectorXd& q) {
  return (q.array() >= model.lower_limits().array()).all() &&
         (q.array() <= model.upper_limits().array()).all();
}

Eigen::VectorXd cost_gradient(const RobotModel& model, const Eigen::VectorXd& q,
                              const Eigen::VectorXd& p, const RedundancyOptions& o) {
  Eigen::VectorXd g = q - p;
  for (int i = 0; i < model.dof(); ++i) {
    if (!penalized(model, i) || o.limit_weight == 0.0) continue;
    const double lo = model.lower_limits()[i], hi = model.upper_limits()[i];
    const double m = o.limit_margin * (hi - lo);
    const double below = std::max(0.0, m - (q[i] - lo));
    const double above = std::max(0.0, m - (hi - q[i]));
    g[i] += o.limit_weight * 2.0 * (above - below) / (m * m);
  }
  return g;
}

// Pose error and Jacobian at q (data updated).
void linearize(const RobotModel& model, KinematicsData& data, const Eigen::VectorXd& q,
               const Eigen::Isometry3d& T, Vector6d& e, Jacobian& J) {
  forward_kinematics(model, data, q);
  e = pose_error_in_base(data.T_base_tool, T);
  geometric_jacobian(model, data, JacobianFrame::kBase, J);
}

bool converged(const Vector6d& e, double tolerance) {
  return e.head<3>().norm() <= tolerance && e.tail<3>().norm() <= tolerance;
}

// Newton steps q += J^+ e until the pose error is below the tolerance; false when that
// fails or q leaves the limits.
bool restore_pose(const RobotModel& model, KinematicsData& data, const Eigen::Isometry3d& T,
                  double tolerance, Eigen::VectorXd& q, Jacobian& J) {
  Vector6d e;
  for (int k = 0; k <= kCorrections; ++k) {
    linearize(model, data, q, T, e, J);
    if (converged(e, tolerance)) return inside(model, q);
    if (k == kCorrections) break;
    Eigen::Matrix<double, 6, 6> gram = J * J.transpose();
    gram.diagonal().array() += kGramDamping;
    q += J.transpose() * gram.ldlt().solve(e);
  }
  return false;
}

Status check_positive(const char* field, double value) {
  if (value > 0.0 && std::isfinite(value)) return Status::Ok();
  return Error{std::string("RedundancyOptions::") + field + " must be positive and finite, got " +
               format_number(value)};
}

}  // namespace

Status check_redundancy_options(const RobotModel& model, const RedundancyOptions& o) {
  if (!(o.limit_margin > 0.0 && o.limit_margin <= 0.5)) {
    return Error{"RedundancyOptions::limit_margin must be in (0, 0.5], got " +
                 format_number(o.limit_margin)};
  }
  if (!(o.limit_weight >= 0.0 && std::isfinite(o.limit_weight))) {
    return Error{"RedundancyOptions::limit_weight must be finite and non-negative, got " +
                 format_number(o.limit_weight)};
  }
  if (o.max_iterations <= 0) {
    return Error{"RedundancyOptions::max_iterations must be positive, got " +
                 std::to_string(o.max_iterations)};
  }
  if (Status s = check_positive("step_tolerance", o.step_tolerance); !s) return s;
  if (Status s = check_positive("pose_tolerance", o.pose_tolerance); !s) return s;
  if (o.preference == NullSpacePreference::kRest) {
    if (o.rest_q.size() != model.dof()) {
      return Error{"RedundancyOptions::rest_q has " + std::to_string(o.rest_q.size()) +
                   " values, expected " + std::to_string(model.dof()) + " (one per joint of " +
                   model.name() + ")"};
    }
    for (int i = 0; i < model.dof(); ++i) {
      const double v = o.rest_q[i];
      if (!std::isfinite(v) || v < model.lower_limits()[i] || v > model.upper_limits()[i]) {
        return Error{"RedundancyOptions::rest_q[" + std::to_string(i) + "] = " + format_number(v) +
                     " is not within the limits of joint " + std::to_string(i + 1) + " (" +
                     model.joint(i).name + ")"};
      }
    }
  }
  return Status::Ok();
}

double null_space_cost(const RobotModel& model, const Eigen::VectorXd& q, const Eigen::VectorXd& p,
                       const RedundancyOptions& o) {
  double h = 0.5 * (q - p).squaredNorm();
  for (int i = 0; i < model.dof(); ++i) {
    if (!penalized(model, i) || o.limit_weight == 0.0) continue;
    const double lo = model.lower_limits()[i], hi = model.upper_limits()[i];
    const double m = o.limit_margin * (hi - lo);
    const double below = std::max(0.0, m - (q[i] - lo)) / m;
    const double above = std::max(0.0, m - (hi - q[i])) / m;
    h += o.limit_weight * (below * below + above * above);
  }
  return h;
}

NullSpaceResult optimize_null_space(const RobotModel& model, const Eigen::Isometry3d& T,
                                    const Eigen::VectorXd& q_solution, const Eigen::VectorXd& p,
                                    const RedundancyOptions& o) {
  KinematicsData data(model);
  Jacobian J(6, model.dof());
  NullSpaceResult result;
  result.q = q_solution;
  // First the pose itself, to pose_tolerance (the caller's solution may be looser).
  Eigen::VectorXd q = q_solution;
  if (restore_pose(model, data, T, o.pose_tolerance, q, J)) result.q = q;
  q = result.q;
  double h = null_space_cost(model, q, p, o);
  result.cost_before = h;
  if (model.dof() > 6) {
    Eigen::VectorXd trial(model.dof());
    Jacobian J_trial(6, model.dof());
    for (int it = 0; it < o.max_iterations; ++it) {
      ++result.iterations;
      forward_kinematics(model, data, q);
      geometric_jacobian(model, data, JacobianFrame::kBase, J);
      const Eigen::VectorXd g = cost_gradient(model, q, p, o);
      Eigen::Matrix<double, 6, 6> gram = J * J.transpose();
      gram.diagonal().array() += kGramDamping;
      const Eigen::VectorXd projected = g - J.transpose() * gram.ldlt().solve(J * g);
      if (projected.cwiseAbs().maxCoeff() <= o.step_tolerance) break;
      double alpha = 1.0;
      bool accepted = false;
      double step = 0.0;
      for (int halving = 0; halving < kHalvings; ++halving, alpha *= 0.5) {
        trial = q - alpha * projected;
        if (!inside(model, trial)) continue;
        if (!restore_pose(model, data, T, o.pose_tolerance, trial, J_trial)) continue;
        const double h_trial = null_space_cost(model, trial, p, o);
        if (h_trial < h) {
          step = (trial - q).cwiseAbs().maxCoeff();
          q = trial;
          h = h_trial;
          accepted = true;
          break;
        }
      }
      if (!accepted || step <= o.step_tolerance) break;
    }
  }
  result.q = q;
  result.cost_after = h;
  return result;
}

}  // namespace telear::core
