#include "telear/core/ik_numeric.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <vector>

#include "telear/core/seeded_random.hpp"

namespace telear::core {

// The solver's state behind a small interface, so that 6- and 7-joint arms get fixed-size Eigen
// types (unrolled products and factorizations) and other arms dynamic ones.
class NumericIkSolver::Workspace {
 public:
  virtual ~Workspace() = default;
  virtual NumericIkResult solve(const Eigen::Isometry3d& T_target,
                                const Eigen::VectorXd& q_seed) = 0;
};

namespace {

constexpr double kInitialMu = 0.1;
constexpr double kMuDecrease = 0.5;
constexpr double kMuIncrease = 8.0;
constexpr double kMinMu = 1e-3;
// An accepted step that keeps more than this fraction of the cost counts as slow; while a joint
// is held at a limit, more than the second (the attempt is likely trapped there).
constexpr double kSlowProgress = 0.95;
constexpr double kSlowProgressHeld = 0.5;
// Geodesic acceleration: finite-difference step along dq, and the largest accepted ratio
// 2 |a| / |dq| (Transtrum & Sethna's alpha).
constexpr double kAccelerationProbe = 0.1;
constexpr double kMaxAccelerationRatio = 0.75;

// Pose error [dp; log(R_target R^T)] in the base frame. The SO(3) logarithm directly from the
// skew part (2 sin(theta) axis) and the trace (1 + 2 cos(theta)); near theta = pi, where the
// skew part vanishes, through Eigen's quaternion route instead.
void pose_error(const Eigen::Isometry3d& T_target, const Eigen::Isometry3d& T, Vector6d& e) {
  e.head<3>() = T_target.translation() - T.translation();
  const Eigen::Matrix3d R = T_target.linear() * T.linear().transpose();
  const double cosine = 0.5 * (R.trace() - 1.0);
  if (cosine < -0.99) {
    const Eigen::AngleAxisd aa(R);
    e.tail<3>() = aa.angle() * aa.axis();
    return;
  }
  const Eigen::Vector3d skew(R(2, 1) - R(1, 2), R(0, 2) - R(2, 0), R(1, 0) - R(0, 1));
  const double sine = 0.5 * skew.norm();
  const double theta = std::atan2(sine, cosine);
  // theta / sin(theta), by its series where the division would lose digits.
  const double ratio = sine > 1e-6 ? theta / sine : 1.0 + theta * theta / 6.0;
  e.tail<3>() = (0.5 * ratio) * skew;
}

// N: the number of joints at compile time, or Eigen::Dynamic.
template <int N>
class LevenbergMarquardt final : public NumericIkSolver::Workspace {
 public:
  using Vec = Eigen::Matrix<double, N, 1>;
  using Mat = Eigen::Matrix<double, N, N>;
  using Jac = Eigen::Matrix<double, 6, N>;

  LevenbergMarquardt(const RobotModel& model, const NumericIkOptions& options)
      : model_(model),
        options_(options),
        n_(model.dof()),
        data_(model),
        q_fk_(model.dof()),
        J_dynamic_(6, model.dof()),
        J_(Jac::Zero(6, n_)),
        JtJ_(Mat::Zero(n_, n_)),
        A_(Mat::Zero(n_, n_)),
        diagonal_(Vec::Zero(n_)),
        inverse_diagonal_(Vec::Zero(n_)),
        row_times_d_(Vec::Zero(n_)),
        Jte_(Vec::Zero(n_)),
        g_(Vec::Zero(n_)),
        lower_(model.lower_limits()),
        upper_(model.upper_limits()),
        sample_lower_(Vec::Zero(n_)),
        sample_upper_(Vec::Zero(n_)),
        held_step_(Vec::Zero(n_)),
        q_(Vec::Zero(n_)),
        q_trial_(Vec::Zero(n_)),
        dq_(Vec::Zero(n_)),
        acceleration_(Vec::Zero(n_)),
        best_q_(Vec::Zero(n_)),
        wraps_(static_cast<size_t>(n_)),
        held_(static_cast<size_t>(n_)) {
    for (int i = 0; i < n_; ++i) {
      const bool finite = std::isfinite(lower_[i]) && std::isfinite(upper_[i]);
      sample_lower_[i] = finite ? lower_[i] : -std::numbers::pi;
      sample_upper_[i] = finite ? upper_[i] : std::numbers::pi;
      wraps_[static_cast<size_t>(i)] = model.joint(i).type == JointType::kRevolute && finite &&
                                       upper_[i] - lower_[i] >= 2.0 * std::numbers::pi;
    }
  }

  NumericIkResult solve(const Eigen::Isometry3d& T_target, const Eigen::VectorXd& q_seed) override;

 private:
  // Forward kinematics at q and the pose error; returns the cost e^T e / 2.
  double evaluate(const Vec& q, const Eigen::Isometry3d& T_target, Vector6d& e) {
    q_fk_ = q;
    forward_kinematics(model_, data_, q_fk_);
    pose_error(T_target, data_.T_base_tool, e);
    return 0.5 * e.squaredNorm();
  }
  bool attempt(const Eigen::Isometry3d& T_target, int& iterations);
  // J, J^T J and J^T e at q_ (data_ must hold q_'s frames).
  void linearize(const Vector6d& e);
  // dq_ from the linearization with damping lambda, holding joints at their limits (active
  // set); leaves the factorization of the final system in A_.
  void damped_step(double lambda);
  void factorize();
  void substitute(const Vec& b, Vec& x) const;
  void accelerate(const Eigen::Isometry3d& T_target, const Vector6d& e);
  void take_step(Vec& q) const;
  void clamp(Vec& q) const { q = q.cwiseMax(lower_).cwiseMin(upper_); }
  // The joint count, a compile-time constant for fixed N (so loops over joints unroll).
  int size() const { return N == Eigen::Dynamic ? n_ : N; }

  const RobotModel& model_;
  const NumericIkOptions options_;
  const int n_;
  KinematicsData data_;
  Eigen::VectorXd q_fk_;  // forward_kinematics takes a dynamic vector
  Jacobian J_dynamic_;    // geometric_jacobian's output, copied into J_
  Jac J_;
  Mat JtJ_;
  Mat A_;         // damped normal matrix; L of its L D L^T factorization (strict lower triangle)
  Vec diagonal_;  // D_ii
  Vec inverse_diagonal_;  // 1 / D_ii
  Vec row_times_d_;       // factorize()'s scratch
  Vec Jte_, g_;
  Vec lower_, upper_, sample_lower_, sample_upper_;
  Vec held_step_;
  Vec q_, q_trial_, dq_, acceleration_, best_q_;
  std::vector<char> wraps_;  // joint i: revolute with limits spanning >= 2 pi
  std::vector<char> held_;   // joint i held at a limit in the current step (active set)
  bool any_held_ = false;
  std::uint64_t rng_state_ = 0;
  double best_cost_ = 0.0;
};

template <int N>
void LevenbergMarquardt<N>::factorize() {
  // A = L D L^T in place (A is positive definite thanks to the damping): L unit lower
  // triangular in A_'s strict lower triangle, 1 / D in inverse_diagonal_. No square roots, and
  // substitution multiplies instead of divides. The loops are unrolled for fixed N: their
  // varying trip counts otherwise cost more in mispredicted branches than the arithmetic.
  const int n = size();
#pragma GCC unroll 8
  for (int j = 0; j < n; ++j) {
    // Row j of L times D, reused for every row below.
#pragma GCC unroll 8
    for (int k = 0; k < j; ++k) row_times_d_[k] = A_(j, k) * diagonal_[k];
    double d = A_(j, j);
#pragma GCC unroll 8
    for (int k = 0; k < j; ++k) d -= A_(j, k) * row_times_d_[k];
    d = std::max(d, std::numeric_limits<double>::min());
    const double inverse = 1.0 / d;
    diagonal_[j] = d;
    inverse_diagonal_[j] = inverse;
#pragma GCC unroll 8
    for (int i = j + 1; i < n; ++i) {
      double s = A_(i, j);
#pragma GCC unroll 8
      for (int k = 0; k < j; ++k) s -= A_(i, k) * row_times_d_[k];
      A_(i, j) = s * inverse;
    }
  }
}

template <int N>
void LevenbergMarquardt<N>::substitute(const Vec& b, Vec& x) const {
  const int n = size();
#pragma GCC unroll 8
  for (int i = 0; i < n; ++i) {  // L y = b
    double s = b[i];
#pragma GCC unroll 8
    for (int k = 0; k < i; ++k) s -= A_(i, k) * x[k];
    x[i] = s;
  }
#pragma GCC unroll 8
  for (int i = n - 1; i >= 0; --i) {  // L^T x = D^-1 y
    double s = x[i] * inverse_diagonal_[i];
#pragma GCC unroll 8
    for (int k = i + 1; k < n; ++k) s -= A_(k, i) * x[k];
    x[i] = s;
  }
}

template <int N>
void LevenbergMarquardt<N>::linearize(const Vector6d& e) {
  geometric_jacobian(model_, data_, JacobianFrame::kBase, J_dynamic_);
  J_ = J_dynamic_;
  JtJ_.noalias() = J_.transpose() * J_;
  Jte_.noalias() = J_.transpose() * e;
}

template <int N>
void LevenbergMarquardt<N>::damped_step(double lambda) {
  std::fill(held_.begin(), held_.end(), 0);
  any_held_ = false;
  // Each pass holds at least one more joint, so at most n + 1 passes.
  for (int pass = 0; pass <= n_; ++pass) {
    A_ = JtJ_;
    A_.diagonal().array() += lambda;
    g_ = Jte_;
    if (any_held_) {
      // Held joints move by held_step_ exactly: their columns go to the right-hand side and
      // their equations become dq_i = held_step_i.
      for (int i = 0; i < n_; ++i) {
        if (held_[static_cast<size_t>(i)]) g_ -= A_.col(i) * held_step_[i];
      }
      for (int i = 0; i < n_; ++i) {
        if (!held_[static_cast<size_t>(i)]) continue;
        A_.row(i).setZero();
        A_.col(i).setZero();
        A_(i, i) = 1.0;
        g_[i] = held_step_[i];
      }
    }
    factorize();
    substitute(g_, dq_);
    bool newly_held = false;
    for (int i = 0; i < n_; ++i) {
      const size_t k = static_cast<size_t>(i);
      if (held_[k] || wraps_[k]) continue;
      if (q_[i] + dq_[i] < lower_[i]) {
        held_step_[i] = lower_[i] - q_[i];
      } else if (q_[i] + dq_[i] > upper_[i]) {
        held_step_[i] = upper_[i] - q_[i];
      } else {
        continue;
      }
      held_[k] = 1;
      newly_held = any_held_ = true;
    }
    if (!newly_held) break;
  }
  // Scaling keeps the step within the box: q_ and q_ + dq_ both are (convexity).
  const double largest = dq_.cwiseAbs().maxCoeff();
  if (largest > options_.max_step_rad) dq_ *= options_.max_step_rad / largest;
}

template <int N>
void LevenbergMarquardt<N>::accelerate(const Eigen::Isometry3d& T_target, const Vector6d& e) {
  // Second directional derivative of e along dq by finite differences:
  // e(q + h dq) = e - h J dq + h^2 / 2 e_vv.
  const double h = kAccelerationProbe;
  q_trial_ = q_ + h * dq_;
  Vector6d e_h;
  evaluate(q_trial_, T_target, e_h);
  const Vector6d e_vv = (2.0 / (h * h)) * (e_h - e + h * (J_ * dq_));
  // Acceleration: (J^T J + lambda I) a = J^T e_vv, held joints not accelerating; the
  // system's factorization is still in A_.
  g_.noalias() = J_.transpose() * e_vv;
  for (int i = 0; i < n_; ++i) {
    if (held_[static_cast<size_t>(i)]) g_[i] = 0.0;
  }
  substitute(g_, acceleration_);
  if (2.0 * acceleration_.norm() > kMaxAccelerationRatio * dq_.norm()) return;
  dq_ += 0.5 * acceleration_;
  for (int i = 0; i < n_; ++i) {
    if (wraps_[static_cast<size_t>(i)]) continue;
    dq_[i] = std::clamp(dq_[i], lower_[i] - q_[i], upper_[i] - q_[i]);
  }
}

template <int N>
void LevenbergMarquardt<N>::take_step(Vec& q) const {
  q = q_ + dq_;
  for (int i = 0; i < n_; ++i) {
    if (!wraps_[static_cast<size_t>(i)]) continue;
    // A joint whose limits span 2 pi or more reaches the same pose within them.
    if (q[i] > upper_[i]) q[i] -= 2.0 * std::numbers::pi;
    if (q[i] < lower_[i]) q[i] += 2.0 * std::numbers::pi;
  }
  clamp(q);
}

template <int N>
bool LevenbergMarquardt<N>::attempt(const Eigen::Isometry3d& T_target, int& iterations) {
  const auto converged = [this](const Vector6d& e) {
    return e.head<3>().norm() <= options_.position_tolerance_m &&
           e.tail<3>().norm() <= options_.orientation_tolerance_rad;
  };
  Vector6d e, e_trial;
  double cost = evaluate(q_, T_target, e);
  double mu = kInitialMu;
  int slow = 0;
  bool done = converged(e);
  if (!done) linearize(e);
  for (int it = 0; it < options_.max_iterations && !done; ++it) {
    ++iterations;
    damped_step(mu * (cost + options_.damping_bias));
    if (cost < options_.geodesic_acceleration_below) accelerate(T_target, e);
    take_step(q_trial_);
    const double cost_trial = evaluate(q_trial_, T_target, e_trial);
    if (cost_trial < cost) {
      const double slow_ratio = any_held_ ? kSlowProgressHeld : kSlowProgress;
      slow = cost_trial > slow_ratio * cost ? slow + 1 : 0;
      q_.swap(q_trial_);
      e = e_trial;
      cost = cost_trial;
      mu = std::max(mu * kMuDecrease, kMinMu);
      done = converged(e);
      // data_ holds the new q_'s frames: linearize there before anything moves them.
      if (!done && slow < options_.stall_iterations) linearize(e);
    } else {
      // Rejected: same q_, same linearization, more damping.
      ++slow;
      mu *= kMuIncrease;
    }
    if (slow >= options_.stall_iterations) break;
  }
  if (cost < best_cost_) {
    best_cost_ = cost;
    best_q_ = q_;
  }
  return done;
}

template <int N>
NumericIkResult LevenbergMarquardt<N>::solve(const Eigen::Isometry3d& T_target,
                                             const Eigen::VectorXd& q_seed) {
  NumericIkResult result;
  if (!T_target.matrix().allFinite() || !q_seed.allFinite()) {
    result.q = q_seed;
    result.message = "target pose or seed is not finite";
    return result;
  }
  rng_state_ = options_.seed;
  best_cost_ = std::numeric_limits<double>::infinity();
  q_ = q_seed;
  clamp(q_);
  int iterations = 0;
  int restarts = 0;
  bool converged = attempt(T_target, iterations);
  while (!converged && restarts < options_.max_restarts) {
    ++restarts;
    for (int i = 0; i < n_; ++i) {
      q_[i] = sample_lower_[i] + (sample_upper_[i] - sample_lower_[i]) * uniform01(rng_state_);
    }
    converged = attempt(T_target, iterations);
  }
  result.success = converged;
  result.q = converged ? q_ : best_q_;
  result.iterations = iterations;
  result.restarts = restarts;
  Vector6d e;
  evaluate(result.q, T_target, e);
  result.position_error_m = e.head<3>().norm();
  result.orientation_error_rad = e.tail<3>().norm();
  if (!converged) {
    char buffer[200];
    std::snprintf(buffer, sizeof buffer,
                  "no configuration within the joint limits reaches it after %d attempts "
                  "(%d iterations); the closest is %.3g m, %.3g rad away",
                  restarts + 1, iterations, result.position_error_m, result.orientation_error_rad);
    result.message = buffer;
  }
  return result;
}

}  // namespace

NumericIkSolver::NumericIkSolver(const RobotModel& model, NumericIkOptions options)
    : options_(options), dof_(model.dof()) {
  assert(options_.max_iterations > 0 && options_.max_restarts >= 0 &&
         "NumericIkSolver: max_iterations must be positive, max_restarts non-negative");
  // The common arm sizes get unrolled fixed-size algebra (a 6-joint arm, a 7-joint redundant
  // one); any other chain the dynamic form.
  if (model.dof() == 6) {
    workspace_ = std::make_unique<LevenbergMarquardt<6>>(model, options_);
  } else if (model.dof() == 7) {
    workspace_ = std::make_unique<LevenbergMarquardt<7>>(model, options_);
  } else {
    workspace_ = std::make_unique<LevenbergMarquardt<Eigen::Dynamic>>(model, options_);
  }
}

NumericIkSolver::~NumericIkSolver() = default;
NumericIkSolver::NumericIkSolver(NumericIkSolver&&) noexcept = default;
NumericIkSolver& NumericIkSolver::operator=(NumericIkSolver&&) noexcept = default;

NumericIkResult NumericIkSolver::solve(const Eigen::Isometry3d& T_base_tool,
                                       const Eigen::VectorXd& q_seed) {
  assert(q_seed.size() == dof_ && "NumericIkSolver::solve(): wrong seed size");
  return workspace_->solve(T_base_tool, q_seed);
}

}  // namespace telear::core
