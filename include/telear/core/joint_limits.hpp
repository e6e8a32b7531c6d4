#pragma once
// Bound checks of joint vectors against a model's limits, with messages in the units an
// operator reads (degrees for revolute joints, millimetres for prismatic ones).

#include <Eigen/Core>
#include <optional>
#include <string>

#include "telear/core/robot_model.hpp"

namespace telear::core {

struct LimitViolation {
  int joint = 0;       // 0-based
  double value = 0.0;  // rad or m
  double limit = 0.0;  // the bound it crosses
  bool upper = false;  // true: above the upper limit
};

// The first joint (lowest index) outside [lower - tolerance, upper + tolerance], if any.
std::optional<LimitViolation> first_limit_violation(const RobotModel& model,
                                                    const Eigen::VectorXd& q,
                                                    double tolerance = 0.0);

bool within_limits(const RobotModel& model, const Eigen::VectorXd& q, double tolerance = 0.0);

// Within limits modulo whole turns: a revolute joint's value and value + 2 pi k are the same
// pose, so a solution (IK's answers are wrapped to (-pi, pi]) counts as reachable when some
// 2 pi equivalent lies within [lower - tolerance, upper + tolerance]. Prismatic joints are
// checked as they are. The lowest such equivalent, or nullopt when there is none (rad or m).
std::optional<double> equivalent_within_limits(const RobotModel& model, int joint, double value,
                                               double tolerance = 0.0);

// The same for one angle and bare limits (rad; either may be infinite): the lowest
// value + 2 pi k within [lower - tolerance, upper + tolerance], or nullopt (NaN too).
std::optional<double> angle_equivalent_within(double value, double lower, double upper,
                                              double tolerance = 0.0);

// The first joint (0-based) with no equivalent within its limits, if any.
std::optional<int> first_joint_outside_limits_modulo_turns(const RobotModel& model,
                                                           const Eigen::VectorXd& q,
                                                           double tolerance = 0.0);

bool within_limits_modulo_turns(const RobotModel& model, const Eigen::VectorXd& q,
                                double tolerance = 0.0);

// "joint 2 (shoulder) would be at 120.00 deg, beyond its upper limit of 110.00 deg"
std::string describe_violation(const RobotModel& model, const LimitViolation& violation);

// A joint value in operator units: "12.50 deg" or "30.0 mm".
std::string format_joint_value(const RobotModel& model, int joint, double value);
std::string format_joint_value(JointType type, double value);

// "joint 2 (shoulder)": 1-based, as operators count joints.
std::string joint_label(const RobotModel& model, int joint);

// "1.29167 s": a time in messages, six significant digits.
std::string format_seconds(double seconds);

}  // namespace telear::core
