#pragma once
// Joint values as an operator writes and reads them (--q on every command, the kin tables):
// a named configuration or one number per joint, degrees for revolute joints when asked
// (prismatic joints stay in metres), and the fixed-width row the tables print. Conversion
// goes through angles.hpp; inside telear joint values are radians and metres.

#include <Eigen/Core>
#include <string>

#include "telear/core/result.hpp"
#include "telear/core/robot_model.hpp"

namespace telear::core {

// Revolute joints' values converted from degrees to radians (prismatic ones unchanged).
Eigen::VectorXd joint_values_from_degrees(const RobotModel& model, Eigen::VectorXd q);
// Revolute joints' values converted from radians to degrees (prismatic ones unchanged).
Eigen::VectorXd joint_values_to_degrees(const RobotModel& model, Eigen::VectorXd q);

// `text` is a named configuration of the model ("qn", taken as is) or dof() comma-separated
// numbers (radians, or degrees for revolute joints with `degrees`). Errors are
// parse_number_list's naming `option`, then " (robot 'puma560' has 6 joints)".
Result<Eigen::VectorXd> parse_joint_values(const RobotModel& model, const std::string& text,
                                           const std::string& option, bool degrees);

// "[  1.00,  -2.50]": each value printf'd "%*.*f" with `width` and `precision`, and no
// "-0.00" for a value that rounds to zero.
std::string format_joint_values(const Eigen::VectorXd& q, int width, int precision);

}  // namespace telear::core
