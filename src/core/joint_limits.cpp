#include "telear/core/joint_limits.hpp"

#include <cstdio>

#include "telear/core/angles.hpp"

namespace telear::core {

std::optional<LimitViolation> first_limit_violation(const RobotModel& model,
                                                    const Eigen::VectorXd& q, double tolerance) {
  for (int i = 0; i < model.dof(); ++i) {
    const JointLimits& l = model.joint(i).limits;
    if (q[i] < l.lower - tolerance) return LimitViolation{i, q[i], l.lower, false};
    if (q[i] > l.upper + tolerance) return LimitViolation{i, q[i], l.upper, true};
  }
  return std::nullopt;
}

bool within_limits(const RobotModel& model, const Eigen::VectorXd& q, double tolerance) {
  return !first_limit_violation(model, q, tolerance).has_value();
}

std::string format_joint_value(const RobotModel& model, int joint, double value) {
  return format_joint_value(model.joint(joint).type, value);
}

std::string format_joint_value(JointType type, double value) {
  char buffer[64];
  if (type == JointType::kRevolute) {
    std::snprintf(buffer, sizeof buffer, "%.2f deg", degrees_from_radians(value));
  } else {
    std::snprintf(buffer, sizeof buffer, "%.1f mm", value * 1000.0);
  }
  return buffer;
}

std::string joint_label(const RobotModel& model, int joint) {
  return "joint " + std::to_string(joint + 1) + " (" + model.joint(joint).name + ")";
}

std::string format_seconds(double seconds) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6g s", seconds);
  return buffer;
}

std::string describe_violation(const RobotModel& model, const LimitViolation& v) {
  return joint_label(model, v.joint) + " would be at " +
         format_joint_value(model, v.joint, v.value) + ", beyond its " +
         (v.upper ? "upper" : "lower") + " limit of " + format_joint_value(model, v.joint, v.limit);
}

}  // namespace telear::core
