#pragma once
// Inverse kinematics as motion commands use it: the solution nearest the current
// configuration that respects the joint limits.
//
// Arms with PUMA geometry (ik_analytic.hpp) or UR geometry (ik_ur.hpp: three parallel middle
// axes, detected from the joints whatever file they came from) use their closed form: all
// solutions (8 at most), and for each joint the 2*pi-equivalent value within the limits
// nearest q_current; the solution nearest q_current (Euclidean joint distance) wins. At an
// exact wrist singularity only q4 +- q6 (PUMA) or q6 and q2 + q3 + q4 together (UR) are
// determined, so q4 (PUMA) or q6 (UR) stays at its current value. Other arms use
// NumericIkSolver seeded at
// q_current, then random restarts, asking for 1e-9 m / 1e-9 rad and settling for the solver's
// default 1e-6 where that fails (slow convergence next to a singular target); revolute joints
// are then moved to their 2*pi-equivalent nearest q_current within the limits, and `singular`
// is set when the smallest singular value of the Jacobian there is below 1e-6.
//
// Redundant arms (more than six joints) then move that solution along the self-motion
// manifold to the null-space preference of `redundancy` (ik_redundant.hpp: near q_current by
// default, or near a rest pose, away from the joint limits), config "redundant"; since that
// search restores the pose to 1e-10 itself, their LM asks for its default 1e-6 first, and the
// 1e-9 route above runs only where the result does not reach 1e-9. Six-joint arms list all
// their branches with solve_ik_all (ik_branches.hpp): the closed form's, or found by search.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "telear/core/ik_analytic.hpp"
#include "telear/core/ik_redundant.hpp"
#include "telear/core/result.hpp"
#include "telear/core/robot_model.hpp"

namespace telear::core {

// The nearest in-limit solution (config "lun" ... "rdf" from a closed form, "numeric" or
// "redundant"; `singular` set near a singularity), or an error saying the target is
// unreachable or every solution leaves the joint limits, and why. q_current must pass
// check_joint_vector.
Result<IkSolution> solve_ik_nearest(const RobotModel& model, const Eigen::Isometry3d& T_base_tool,
                                    const Eigen::VectorXd& q_current);

// The same with the redundancy resolution's options (used for dof > 6 only; an error naming
// the field when they fail check_redundancy_options).
Result<IkSolution> solve_ik_nearest(const RobotModel& model, const Eigen::Isometry3d& T_base_tool,
                                    const Eigen::VectorXd& q_current,
                                    const RedundancyOptions& redundancy);

}  // namespace telear::core
