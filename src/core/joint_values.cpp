#include "telear/core/joint_values.hpp"

#include <cmath>

#include "telear/core/angles.hpp"
#include "telear/core/number_format.hpp"
#include "telear/core/number_list.hpp"

namespace telear::core {

Eigen::VectorXd joint_values_from_degrees(const RobotModel& model, Eigen::VectorXd q) {
  for (int i = 0; i < model.dof(); ++i) {
    if (model.joint(i).type == JointType::kRevolute) q[i] = radians_from_degrees(q[i]);
  }
  return q;
}

Eigen::VectorXd joint_values_to_degrees(const RobotModel& model, Eigen::VectorXd q) {
  for (int i = 0; i < model.dof(); ++i) {
    if (model.joint(i).type == JointType::kRevolute) q[i] = degrees_from_radians(q[i]);
  }
  return q;
}

Result<Eigen::VectorXd> parse_joint_values(const RobotModel& model, const std::string& text,
                                           const std::string& option, bool degrees) {
  if (auto named = model.named_configuration(text)) return *named;
  auto values = parse_number_list(text, option, model.dof());
  if (!values) {
    return Error{values.error().message + " (robot '" + model.name() + "' has " +
                 std::to_string(model.dof()) + " joints)"};
  }
  const Eigen::VectorXd q = to_vector(*values);
  return degrees ? joint_values_from_degrees(model, q) : q;
}

std::string format_joint_values(const Eigen::VectorXd& q, int width, int precision) {
  std::string text = "[";
  // Appended piece by piece: GCC 12 warns (-Wstringop-overflow) on a "literal" + string chain.
  std::string format = "%";
  format += std::to_string(width);
  format += '.';
  format += std::to_string(precision);
  format += 'f';
  const double zero = 0.5 * std::pow(10.0, -precision);
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    const double value = std::abs(q[i]) < zero ? 0.0 : q[i];
    text += (i ? ", " : "") + format_number(value, format.c_str());
  }
  return text + "]";
}

}  // namespace telear::core
