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

constexpr int kCorrections = 8;         // Newton steps restoring the pose after a step
constexpr int kHalvings = 30;           // of alpha, before giving up on a direction
constexpr double kGramDamping = 1e-12;  // keeps J J^T invertible at a singularity
// Bounds of the Barzilai-Borwein step length (a nearly flat or folded self-motion).
constexpr double kMinAlpha = 1e-3;
constexpr double kMaxAlpha = 1e3;

// The penalty acts on joint i when its limits are finite and span less than a full turn.
bool penalized(const RobotModel& model, int i) {
  const double lo = model.lower_limits()[i], hi = model.upper_limits()[i];
  return std::isfinite(lo) && std::isfinite(hi) &&
         !(model.joint(i).type == JointType::kRevolute && hi - lo >= 2.0 * std::numbers::pi) &&
         hi > lo;
}

bool converged(const Vector6d& e, double tolerance) {
  return e.head<3>().norm() <= tolerance && e.tail<3>().norm() <= tolerance;
}

// The search's state, with joint vectors and the Jacobian in buffers of fixed capacity for
// arms of up to kMaxFixedJoints joints (MaxN), so that no iteration touches the heap; longer
// chains use dynamic ones (MaxN = Eigen::Dynamic), allocated once per call.
constexpr int kMaxFixedJoints = 8;

template <int MaxN>
class NullSpaceSearch {
 public:
  using Vec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, MaxN, 1>;
  using Jac = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, MaxN>;

  NullSpaceSearch(const RobotModel& model, const Eigen::Isometry3d& T, const Eigen::VectorXd& p,
                  const RedundancyOptions& o)
      : model_(model),
        T_(T),
        o_(o),
        n_(model.dof()),
        data_(model),
        q_fk_(model.dof()),
        J_fk_(6, model.dof()),
        p_(p),
        lower_(model.lower_limits()),
        upper_(model.upper_limits()),
        margin_(Vec::Zero(n_)),
        penalized_(Vec::Zero(n_)) {
    for (int i = 0; i < n_; ++i) {
      if (!penalized(model, i) || o.limit_weight == 0.0) continue;
      penalized_[i] = 1.0;
      margin_[i] = o.limit_margin * (upper_[i] - lower_[i]);
    }
  }

  NullSpaceResult run(const Eigen::VectorXd& q_solution);

 private:
  bool inside(const Vec& q) const {
    return (q.array() >= lower_.array()).all() && (q.array() <= upper_.array()).all();
  }
  double cost(const Vec& q) const {
    double h = 0.5 * (q - p_).squaredNorm();
    for (int i = 0; i < n_; ++i) {
      if (penalized_[i] == 0.0) continue;
      const double below = std::max(0.0, margin_[i] - (q[i] - lower_[i])) / margin_[i];
      const double above = std::max(0.0, margin_[i] - (upper_[i] - q[i])) / margin_[i];
      h += o_.limit_weight * (below * below + above * above);
    }
    return h;
  }
  // Projected gradient (I - J^+ J) grad h(q), J^+ = J^T (J J^T)^-1: the steepest ascent of h
  // along the self-motion, to first order.
  void projected_gradient(const Vec& q, const Jac& J, Vec& d) const {
    d = q - p_;
    for (int i = 0; i < n_; ++i) {
      if (penalized_[i] == 0.0) continue;
      const double below = std::max(0.0, margin_[i] - (q[i] - lower_[i]));
      const double above = std::max(0.0, margin_[i] - (upper_[i] - q[i]));
      d[i] += o_.limit_weight * 2.0 * (above - below) / (margin_[i] * margin_[i]);
    }
    const Vector6d Jd = J * d;
    d.noalias() -= J.transpose() * gram(J).ldlt().solve(Jd);
  }
  static Eigen::Matrix<double, 6, 6> gram(const Jac& J) {
    Eigen::Matrix<double, 6, 6> G;
    G.noalias() = J * J.transpose();
    G.diagonal().array() += kGramDamping;
    return G;
  }
  // Pose error and Jacobian at q (data_ updated).
  void linearize(const Vec& q, Vector6d& e, Jac& J) {
    q_fk_ = q;
    forward_kinematics(model_, data_, q_fk_);
    e = pose_error_in_base(data_.T_base_tool, T_);
    geometric_jacobian(model_, data_, JacobianFrame::kBase, J_fk_);
    J = J_fk_;
  }
  // Newton steps q += J^+ e until the pose error is below the tolerance; false when that
  // fails or q leaves the limits. J is left at the final q: the next projection reuses it.
  bool restore_pose(Vec& q, Jac& J) {
    Vector6d e;
    for (int k = 0; k <= kCorrections; ++k) {
      linearize(q, e, J);
      if (converged(e, o_.pose_tolerance)) return inside(q);
      if (k == kCorrections) break;
      q.noalias() += J.transpose() * gram(J).ldlt().solve(e);
    }
    return false;
  }

  const RobotModel& model_;
  const Eigen::Isometry3d& T_;
  const RedundancyOptions& o_;
  const int n_;
  KinematicsData data_;
  Eigen::VectorXd q_fk_;  // forward_kinematics takes a dynamic vector
  Jacobian J_fk_;         // geometric_jacobian's output
  const Vec p_, lower_, upper_;
  Vec margin_, penalized_;  // per joint: the penalty's band, and 1 where it acts
};

template <int MaxN>
NullSpaceResult NullSpaceSearch<MaxN>::run(const Eigen::VectorXd& q_solution) {
  NullSpaceResult result;
  Jac J(6, n_), J_trial(6, n_);
  // First the pose itself, to pose_tolerance (the caller's solution may be looser).
  Vec q = q_solution;
  if (!restore_pose(q, J)) {
    q = q_solution;
    Vector6d e;
    linearize(q, e, J);
  }
  double h = cost(q);
  result.cost_before = h;
  if (n_ > 6) {
    Vec d(n_), d_trial(n_), trial(n_), s(n_);
    projected_gradient(q, J, d);
    // Step length: 1 first (the Newton step of the quadratic preference term on a flat
    // self-motion), then Barzilai-Borwein's s^T s / s^T y from the last accepted step s and
    // the change y of the projected gradient: the secant estimate of the curvature along the
    // self-motion, which the flat model misses (a Newton step on the swivel angle of a 7-joint
    // arm: superlinear where fixed steps crawl along a curved self-motion).
    double alpha = 1.0;
    for (int it = 0; it < o_.max_iterations; ++it) {
      ++result.iterations;
      if (d.cwiseAbs().maxCoeff() <= o_.step_tolerance) break;
      bool accepted = false;
      double h_trial = h;
      for (int halving = 0; halving < kHalvings; ++halving, alpha *= 0.5) {
        trial = q - alpha * d;
        if (!inside(trial)) continue;
        if (!restore_pose(trial, J_trial)) continue;
        h_trial = cost(trial);
        if (h_trial < h) {
          accepted = true;
          break;
        }
      }
      if (!accepted) break;
      s = trial - q;
      const double step = s.cwiseAbs().maxCoeff();
      // J_trial is the Jacobian at trial (restore_pose's last linearization).
      projected_gradient(trial, J_trial, d_trial);
      const double sy = s.dot(d_trial - d);
      q = trial;
      h = h_trial;
      J.swap(J_trial);
      d.swap(d_trial);
      if (step <= o_.step_tolerance) break;
      alpha = sy > 0.0 ? std::clamp(s.squaredNorm() / sy, kMinAlpha, kMaxAlpha) : 1.0;
    }
  }
  result.q = q;
  result.cost_after = h;
  return result;
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
  if (model.dof() <= kMaxFixedJoints) {
    return NullSpaceSearch<kMaxFixedJoints>(model, T, p, o).run(q_solution);
  }
  return NullSpaceSearch<Eigen::Dynamic>(model, T, p, o).run(q_solution);
}

}  // namespace telear::core
