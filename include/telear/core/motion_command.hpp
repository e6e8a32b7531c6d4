#pragma once
// The seed paper's motion commands (section 2.6) as pure functions:
//
//   (model, q_current, command) -> MotionOutcome { accepted, q, rejection, singularity }
//
// A command is one of
//   JointIncrement     q_i += delta                       (rad or m)
//   JointTarget        q = target                          (dof values)
//   CartesianIncrement {dX (m), dM (rotation vector, rad)} in the BASE, WRIST or TOOL frame
//   CartesianTarget    T_base_tool = {X, M}
//
// Cartesian increments, with T = T_base_tool(q_current), F = T_base_flange(q_current) and
// Exp(dX, dM) the transform with rotation exp(dM) and translation dX:
//   BASE:  the tool point moves by dX along the base axes and the tool turns by dM about base
//          axes through the tool point:  p' = p + dX,  R' = exp(dM) R.
//   WRIST: dX and dM are expressed in the flange (last link) frame and the turn is about the
//          flange origin; the tool follows rigidly:  T' = F Exp(dX, dM) T_flange_tool.
//   TOOL:  dX and dM are expressed in the tool frame, the turn is about the tool point:
//          T' = T Exp(dX, dM).
// Cartesian commands go through solve_ik_nearest (telear/core/inverse_kinematics.hpp): the solution
// within the joint limits nearest q_current.
//
// No partial motion: a command is applied whole or rejected, and on rejection q is q_current.
// Rejected are: non-finite or wrongly sized input, a joint index out of range, a target that
// is not a rigid transform, a new configuration with a joint beyond its limits (the bound
// check names the joint, its value and the limit), a pose without an IK solution within the
// limits, and, only when MotionOptions::reject_singular_cartesian is set, a Cartesian command
// ending at a singularity. The straight joint-space path from q_current to q (the path
// telear/core/trajectory.hpp follows) stays within the limits because both ends do.
//
// Singularities are reported, not rejected, by default: telear moves the arm along straight
// joint-space lines at bounded joint speeds, so passing a singularity causes no speed burst;
// it only means the Cartesian frame loses a direction there and the IK's choice there is one
// of many (at the PUMA's wrist singularity q4 keeps its current value). The measure is the
// smallest singular value of the 6 x n geometric Jacobian (mixed units: m and rad per rad,
// invariant to the reference point's frame), sampled along that path; below
// singularity_warning_threshold the outcome carries a warning that says where and how close.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <variant>

#include "telear/core/ik_redundant.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/robot_model.hpp"

namespace telear::core {

enum class MotionFrame { kBase, kWrist, kTool };

struct JointIncrement {
  int joint = 0;       // 0-based index
  double delta = 0.0;  // rad or m
};

struct JointTarget {
  Eigen::VectorXd q;  // dof values, rad or m
};

struct CartesianIncrement {
  MotionFrame frame = MotionFrame::kBase;
  Eigen::Vector3d dX = Eigen::Vector3d::Zero();  // m, in `frame`'s axes
  Eigen::Vector3d dM = Eigen::Vector3d::Zero();  // rotation vector, rad, in `frame`'s axes
};

struct CartesianTarget {
  Eigen::Isometry3d T_base_tool = Eigen::Isometry3d::Identity();
};

// The target {X, M}: tool position X (m) and orientation as a rotation vector M (rad), base.
CartesianTarget cartesian_target(const Eigen::Vector3d& X, const Eigen::Vector3d& M);

using MotionCommand =
    std::variant<JointIncrement, JointTarget, CartesianIncrement, CartesianTarget>;

enum class RejectionKind {
  kNone,          // accepted
  kInvalidInput,  // NaN / infinity, wrong size, target not a rigid transform
  kJointIndex,    // JointIncrement::joint out of range
  kJointLimit,    // the new configuration leaves a joint's limits
  kUnreachable,   // no IK solution within the joint limits
  kSingular,      // ends at a singularity (only with reject_singular_cartesian)
};

struct Rejection {
  RejectionKind kind = RejectionKind::kNone;
  int joint = -1;      // 0-based joint concerned, or -1
  double value = 0.0;  // the offending value (rad or m; the index for kJointIndex; the measure
                       // for kSingular)
  double limit = 0.0;  // the bound it crosses (the tolerance for kSingular)
  std::string message;
};

struct SingularityWarning {
  double measure = 0.0;   // smallest Jacobian singular value found along the path
  double fraction = 0.0;  // where: 0 = q_current, 1 = the new q
  std::string message;
};

struct MotionOutcome {
  bool accepted = false;
  Eigen::VectorXd q;    // the new configuration; q_current when rejected
  Rejection rejection;  // kind kNone when accepted
  std::optional<SingularityWarning> singularity;
  std::string ik_config;  // IK branch chosen for a Cartesian command ("lun", "numeric", ...)
};

struct MotionOptions {
  // Warn below this singular value; on the PUMA 560 0.01 is about 1.5 deg from the wrist
  // singularity (q5 = 0), where the measure is about 0.37 |sin q5|.
  double singularity_warning_threshold = 0.01;
  int singularity_samples = 16;  // path samples between q_current and q (both ends included)
  bool reject_singular_cartesian = false;
  double singular_tolerance = 1e-4;  // "at a singularity" for reject_singular_cartesian
  double rigid_tolerance = 1e-6;     // orthonormality tolerance of a CartesianTarget
  double ik_tolerance = 1e-6;        // m and rad: FK(IK(T)) must match T this closely
  // Arms with more than six joints: the null-space preference of Cartesian commands
  // (ik_redundant.hpp; default: stay near q_current). Invalid options reject the command
  // (kInvalidInput, the message names the field).
  RedundancyOptions redundancy = {};
};

// Applies `command` to q_current. q_current must be dof() finite values (else kInvalidInput);
// it may lie outside the limits, but the new configuration may not.
MotionOutcome apply_motion(const RobotModel& model, const Eigen::VectorXd& q_current,
                           const MotionCommand& command, const MotionOptions& options = {});

// The pose a Cartesian increment asks for (see the header comment); pure geometry, no IK.
Eigen::Isometry3d incremented_tool_pose(const RobotModel& model, const KinematicsData& current,
                                        const CartesianIncrement& increment);

// Smallest singular value of the 6 x n geometric Jacobian at q (0 at a singularity).
double jacobian_min_singular_value(const RobotModel& model, KinematicsData& data,
                                   const Eigen::VectorXd& q);

const char* to_string(MotionFrame frame);
const char* to_string(RejectionKind kind);

}  // namespace telear::core
