#pragma once
// Numeric inverse kinematics of any serial arm: Levenberg-Marquardt on the 6-D pose error with
// joint limits and seeded random restarts.
//
// Error (base frame): e = [p_target - p(q); log(R_target R(q)^T)] (metres; rotation vector,
// rad), cost E = e^T e / 2. Each iteration solves the damped normal equations
//
//   (J^T J + lambda I) dq = J^T e,   J = 6 x n geometric Jacobian in the base frame,
//
// with lambda = mu (E + damping_bias) (Sugihara's error-scaled damping) and mu halved after a
// step that lowers E, multiplied by 8 after one that does not (the step is then rejected).
// Joint limits: a joint whose limits span 2 pi or more is wrapped back into them (same pose);
// any other joint that the step would push past a limit is held at that limit and the system
// re-solved for the others (an active set), so the arm slides along the limit instead of
// stalling on it. Near convergence (E below geodesic_acceleration_below) the step gets a
// second-order correction along its own direction (Transtrum & Sethna's geodesic
// acceleration, one extra forward kinematics), which keeps LM moving in the curved valleys
// around singular targets (e.g. the PUMA's folded elbow).
//
// An attempt ends on success, after max_iterations, or after stall_iterations iterations in a
// row that lowered E by less than 5 % (50 % while a joint is held at a limit); the solver then
// restarts from a configuration drawn uniformly within the limits (infinite limits: [-pi, pi]) by a
// generator seeded with `seed` at each solve, so a solve is reproducible whatever came before. The
// solver owns all its buffers: one per thread, no allocation per iteration.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <string>

#include "telear/core/kinematics.hpp"
#include "telear/core/robot_model.hpp"

namespace telear::core {

struct NumericIkOptions {
  int max_iterations = 100;                 // per attempt
  int max_restarts = 200;                   // attempts after the first
  double position_tolerance_m = 1e-6;       // success: |dp| at most this ...
  double orientation_tolerance_rad = 1e-6;  // ... and |log(dR)| at most this
  std::uint64_t seed = 0x7e1ea4;
  double damping_bias = 1e-6;                 // added to E in lambda (bounds the step)
  double max_step_rad = 1.0;                  // largest joint change per iteration (rad or m)
  int stall_iterations = 4;                   // restart after this many slow iterations
  double geodesic_acceleration_below = 1e-4;  // E below which steps get the correction
};

struct NumericIkResult {
  bool success = false;
  Eigen::VectorXd q;   // best configuration found (within limits), rad / m
  int iterations = 0;  // total over all attempts
  int restarts = 0;
  double position_error_m = 0;
  double orientation_error_rad = 0;
  std::string message;  // why it failed; empty on success
};

class NumericIkSolver {
 public:
  // `model` must outlive the solver. Options: max_iterations > 0, max_restarts >= 0.
  explicit NumericIkSolver(const RobotModel& model, NumericIkOptions options = {});
  ~NumericIkSolver();
  NumericIkSolver(NumericIkSolver&&) noexcept;
  NumericIkSolver& operator=(NumericIkSolver&&) noexcept;

  // Seeded at q_seed (clamped into the limits), then restarts. q_seed.size() == dof.
  NumericIkResult solve(const Eigen::Isometry3d& T_base_tool, const Eigen::VectorXd& q_seed);

  const NumericIkOptions& options() const { return options_; }

  // The workspace: fixed-size matrices for 6- and 7-joint arms, dynamic ones otherwise.
  class Workspace;

 private:
  NumericIkOptions options_;
  int dof_ = 0;
  std::unique_ptr<Workspace> workspace_;
};

}  // namespace telear::core
