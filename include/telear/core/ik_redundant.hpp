#pragma once
// Redundancy resolution for arms with more than six joints: among the configurations that
// reach one tool pose (the self-motion manifold, of dimension dof - 6), the one that is a
// local minimum of a preference cost
//
//   h(q) = 1/2 sum_i (q_i - p_i)^2  +  w sum_i [ (max(0, m_i - (q_i - lower_i)) / m_i)^2
//                                              + (max(0, m_i - (upper_i - q_i)) / m_i)^2 ]
//
// p is the preferred configuration (the current one by default: the smallest joint motion;
// or a rest pose), m_i = limit_margin * (upper_i - lower_i) the band next to each limit where
// the joint-limit penalty acts (weight w = limit_weight; none for joints with infinite limits
// or limits spanning 2 pi or more). Starting from a configuration that reaches the pose
// (Levenberg-Marquardt's, ik_numeric.hpp), each iteration takes the projected-gradient step
//
//   dq = -alpha (I - J^+ J) grad h,    J^+ = J^T (J J^T)^-1   (J: 6 x n, base frame)
//
// which leaves the pose unchanged to first order, then restores it exactly with Newton steps
// dq = J^+ e (e: the base-frame pose error), and keeps the step when the result lies within
// the limits and lowers h; otherwise alpha is halved. alpha is 1 at the first step (the Newton
// step of the quadratic preference term), then Barzilai-Borwein's s^T s / s^T y (s: the last
// accepted step, y: the change of the projected gradient over it), a secant estimate of h's
// curvature along the self-motion, so that the search converges superlinearly where the
// self-motion is curved. J^+ comes from a 6 x 6 LDL^T of J J^T; the Jacobian of the last
// restoring step is reused for the next projection. It stops when a step moves no joint by
// more than step_tolerance, when no step lowers h, or after max_iterations. Deterministic: no
// random numbers, and the same input gives the same output. Moving the target a little moves the
// minimum a little, so motion commands (Cartesian jog) do not jump between branches.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "telear/core/result.hpp"
#include "telear/core/robot_model.hpp"

namespace telear::core {

enum class NullSpacePreference {
  kCurrent,  // stay near the configuration the arm is in (the smallest motion)
  kRest,     // stay near RedundancyOptions::rest_q
};

struct RedundancyOptions {
  NullSpacePreference preference = NullSpacePreference::kCurrent;
  Eigen::VectorXd rest_q;         // kRest: dof values within the limits, rad or m
  double limit_margin = 0.1;      // in (0, 0.5]: fraction of a joint's range near each limit
  double limit_weight = 1.0;      // >= 0: weight of the joint-limit penalty
  int max_iterations = 100;       // > 0: projected-gradient steps
  double step_tolerance = 1e-7;   // > 0, rad or m: stop when a step moves no joint more
  double pose_tolerance = 1e-10;  // > 0, m and rad: the pose is kept this exactly
};

// OK, or an error naming the field and why, e.g. "RedundancyOptions::rest_q has 6 values,
// expected 7 (one per joint of arm7)".
Status check_redundancy_options(const RobotModel& model, const RedundancyOptions& options);

// h(q) above, for tests and diagnostics.
double null_space_cost(const RobotModel& model, const Eigen::VectorXd& q,
                       const Eigen::VectorXd& q_preferred, const RedundancyOptions& options);

struct NullSpaceResult {
  Eigen::VectorXd q;  // the local minimum found (q_solution when no step helped)
  int iterations = 0;
  double cost_before = 0.0;  // h at q_solution (after restoring the pose)
  double cost_after = 0.0;   // h at q
};

// Moves q_solution (within the limits, reaching T_base_tool to about 1e-6) along the
// self-motion manifold of T_base_tool to a local minimum of h. Options must pass
// check_redundancy_options; for dof <= 6 only the pose is restored (no null space).
NullSpaceResult optimize_null_space(const RobotModel& model, const Eigen::Isometry3d& T_base_tool,
                                    const Eigen::VectorXd& q_solution,
                                    const Eigen::VectorXd& q_preferred,
                                    const RedundancyOptions& options);

}  // namespace telear::core
