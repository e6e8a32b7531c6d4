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
