#pragma once
// The ghost: the graphical arm the operator moves freely, in safety, before anything is sent to
// the real robot (the seed's "graphical arm"). It is local state only -- a model, a joint
// vector q (dof() values, rad or m) and a gripper opening in [0, 1] (0 closed, 1 open) -- and
// every change goes through the same checks the real robot applies:
//
//   apply(command)        telear/core/motion_command.hpp's apply_motion: joint and Cartesian
//                         increments and targets in the BASE / WRIST / TOOL frames, bound-
//                         checked; a rejection leaves q unchanged and says why.
//   go_to(name)           a named configuration of the model (qz, qr, ...) as a JointTarget;
//                         an unknown name is rejected with the list of known ones.
//   set_gripper(opening)  0..1, validated.
//   reset_to(q)           "ghost = real": q from the robot's reported state, validated.
//
// A plain value class, not thread-safe: the session owns one and serializes access to it.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <string>

#include "telear/core/kinematics.hpp"
#include "telear/core/motion_command.hpp"
#include "telear/core/result.hpp"
#include "telear/core/robot_model.hpp"

namespace telear::session {

class GhostArm {
 public:
  // Starts at q = 0 moved into the joint limits (each joint clamped to [lower, upper]), with the
  // gripper open. `model` must not be null.
  explicit GhostArm(core::RobotModelPtr model, core::MotionOptions options = {});
  // Starts at `q` (validated like reset_to) with the given gripper opening (validated).
  static Result<GhostArm> create(core::RobotModelPtr model, const Eigen::VectorXd& q,
                                 double gripper = 1.0, core::MotionOptions options = {});

  const core::RobotModel& model() const { return *model_; }
  const core::RobotModelPtr& model_ptr() const { return model_; }
  const Eigen::VectorXd& q() const { return q_; }
  double gripper() const { return gripper_; }
  const core::MotionOptions& motion_options() const { return options_; }
  void set_motion_options(const core::MotionOptions& options) { options_ = options; }

  // Applies a motion command. Accepted: q becomes outcome.q (the outcome may carry a
  // singularity warning). Rejected: q is unchanged; outcome.rejection says why.
  core::MotionOutcome apply(const core::MotionCommand& command);

  // Moves to the model's named configuration `name` (a JointTarget through apply()). An unknown
  // name is rejected (kInvalidInput) with a message listing the known names; a configuration
  // outside the limits is rejected like any JointTarget.
  core::MotionOutcome go_to(const std::string& name);

  // Sets the gripper opening; errors for a value that is not finite or outside [0, 1].
  Status set_gripper(double opening);

  // "ghost = real": q must have dof() finite values within the limits (values up to
  // kResetTolerance beyond a limit, rounding in the robot's report, are clamped onto it);
  // the gripper, when given, is validated like set_gripper. Nothing changes on error.
  Status reset_to(const Eigen::VectorXd& q, std::optional<double> gripper = std::nullopt);

  // Poses at the current q (base frame): the tool centre point and the last link (flange),
  // which carries the gripper's marker.
  Eigen::Isometry3d T_base_tool() const;
  Eigen::Isometry3d T_base_flange() const;

  static constexpr double kResetTolerance = 1e-6;  // rad or m

 private:
  core::RobotModelPtr model_;
  core::MotionOptions options_;
  Eigen::VectorXd q_;
  double gripper_ = 1.0;
  mutable core::KinematicsData data_;  // FK cache, re-evaluated incrementally on read
};

// "qz, qr, qs" (the model's named configurations in file order), or "none".
std::string named_configuration_list(const core::RobotModel& model);

}  // namespace telear::session
