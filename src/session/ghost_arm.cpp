#include "telear/session/ghost_arm.hpp"

#include <cassert>
#include <cmath>
#include <cstdio>
#include <utility>

#include "telear/core/joint_limits.hpp"

namespace telear::session {
namespace {

Status check_gripper(double opening) {
  if (!std::isfinite(opening) || opening < 0.0 || opening > 1.0) {
    char text[64];
    std::snprintf(text, sizeof text, "%g", opening);
    return Error{std::string("gripper opening ") + text + " is outside 0 (closed) .. 1 (open)"};
  }
  return Status::Ok();
}

}  // namespace

std::string named_configuration_list(const core::RobotModel& model) {
  std::string list;
  for (const core::NamedConfiguration& c : model.named_configurations()) {
    list += (list.empty() ? "" : ", ") + c.name;
  }
  return list.empty() ? "none" : list;
}

GhostArm::GhostArm(core::RobotModelPtr model, core::MotionOptions options)
    : model_(std::move(model)), options_(options), data_(*model_) {
  assert(model_ && "GhostArm: model must not be null");
  q_ = Eigen::VectorXd::Zero(model_->dof())
           .cwiseMax(model_->lower_limits())
           .cwiseMin(model_->upper_limits());
}

Result<GhostArm> GhostArm::create(core::RobotModelPtr model, const Eigen::VectorXd& q,
                                  double gripper, core::MotionOptions options) {
  GhostArm ghost(std::move(model), options);
  if (Status s = ghost.reset_to(q, gripper); !s) return s.error();
  return ghost;
}

core::MotionOutcome GhostArm::apply(const core::MotionCommand& command) {
  core::MotionOutcome outcome = core::apply_motion(*model_, q_, command, options_);
  if (outcome.accepted) q_ = outcome.q;
  return outcome;
}

core::MotionOutcome GhostArm::go_to(const std::string& name) {
  const std::optional<Eigen::VectorXd> q = model_->named_configuration(name);
  if (!q) {
    core::MotionOutcome outcome;
    outcome.q = q_;
    outcome.rejection.kind = core::RejectionKind::kInvalidInput;
    outcome.rejection.message = "unknown named configuration '" + name + "' of " + model_->name() +
                                "; known: " + named_configuration_list(*model_);
    return outcome;
  }
  core::MotionOutcome outcome = apply(core::JointTarget{*q});
  if (!outcome.accepted) {
    outcome.rejection.message = "named configuration '" + name + "': " + outcome.rejection.message;
  }
  return outcome;
}

Status GhostArm::set_gripper(double opening) {
  if (Status s = check_gripper(opening); !s) return s;
  gripper_ = opening;
  return Status::Ok();
}

Status GhostArm::reset_to(const Eigen::VectorXd& q, std::optional<double> gripper) {
  if (Status s = core::check_joint_vector(*model_, q); !s)
    return Error{"ghost = real: " + s.error().message};
  if (const auto violation = core::first_limit_violation(*model_, q, kResetTolerance)) {
    return Error{"ghost = real: " + core::describe_violation(*model_, *violation)};
  }
  if (gripper) {
    if (Status s = check_gripper(*gripper); !s) return Error{"ghost = real: " + s.error().message};
    gripper_ = *gripper;
  }
  q_ = q.cwiseMax(model_->lower_limits()).cwiseMin(model_->upper_limits());
  return Status::Ok();
}

Eigen::Isometry3d GhostArm::T_base_tool() const {
  core::update_kinematics(*model_, data_, q_);
  return data_.T_base_tool;
}

Eigen::Isometry3d GhostArm::T_base_flange() const {
  core::update_kinematics(*model_, data_, q_);
  return data_.T_base_link.back();
}

}  // namespace telear::session
