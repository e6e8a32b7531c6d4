#include "telear/core/joint_limits.hpp"

#include <cmath>
#include <numbers>

#include "telear/core/angles.hpp"
#include "telear/core/number_format.hpp"

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

std::optional<double> angle_equivalent_within(double value, double lower, double upper,
                                              double tolerance) {
  constexpr double kTurn = 2.0 * std::numbers::pi;
  double v = value;
  if (std::isfinite(v)) {
    if (std::isfinite(lower)) {
      v += kTurn * std::ceil((lower - tolerance - v) / kTurn);  // the lowest one >= lower
    } else if (std::isfinite(upper)) {
      v -= kTurn * std::ceil((v - upper - tolerance) / kTurn);  // the highest one <= upper
    }
  }
  if (!(v >= lower - tolerance && v <= upper + tolerance)) return std::nullopt;  // NaN too
  return v;
}

std::optional<double> equivalent_within_limits(const RobotModel& model, int joint, double value,
                                               double tolerance) {
  const JointLimits& l = model.joint(joint).limits;
  if (model.joint(joint).type == JointType::kRevolute) {
    return angle_equivalent_within(value, l.lower, l.upper, tolerance);
  }
  if (!(value >= l.lower - tolerance && value <= l.upper + tolerance)) return std::nullopt;
  return value;
}

std::optional<int> first_joint_outside_limits_modulo_turns(const RobotModel& model,
                                                           const Eigen::VectorXd& q,
                                                           double tolerance) {
  for (int i = 0; i < model.dof(); ++i) {
    if (!equivalent_within_limits(model, i, q[i], tolerance)) return i;
  }
  return std::nullopt;
}

bool within_limits_modulo_turns(const RobotModel& model, const Eigen::VectorXd& q,
                                double tolerance) {
  return !first_joint_outside_limits_modulo_turns(model, q, tolerance).has_value();
}

std::string format_joint_value(const RobotModel& model, int joint, double value) {
  return format_joint_value(model.joint(joint).type, value);
}

std::string format_joint_value(JointType type, double value) {
  return type == JointType::kRevolute ? format_fixed(degrees_from_radians(value), 2, "deg")
                                      : format_fixed(value * 1000.0, 1, "mm");
}

std::string joint_label(const RobotModel& model, int joint) {
  return "joint " + std::to_string(joint + 1) + " (" + model.joint(joint).name + ")";
}

std::string format_seconds(double seconds) {
  return format_number(seconds, "%.6g") + " s";
}

std::string describe_violation(const RobotModel& model, const LimitViolation& v) {
  return joint_label(model, v.joint) + " would be at " +
         format_joint_value(model, v.joint, v.value) + ", beyond its " +
         (v.upper ? "upper" : "lower") + " limit of " + format_joint_value(model, v.joint, v.limit);
}

}  // namespace telear::core
