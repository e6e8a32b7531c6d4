#include "telear/core/robot_model.hpp"

#include <cmath>
#include <sstream>

#include "telear/core/joint_limits.hpp"

namespace telear::core {
namespace {

bool is_identity_transform(const Eigen::Isometry3d& T) {
  return (T.matrix() - Eigen::Matrix4d::Identity()).cwiseAbs().maxCoeff() == 0.0;
}

// See JointForm. Exact comparisons: a DH form must reproduce `after` to the last bit, apart from
// the quarter-turn snap (|cos alpha| <= 2^-53: only the doubles nearest +-pi/2).
JointForm classify(const Joint& joint) {
  if (joint.type != JointType::kRevolute || !joint.before_is_identity) return JointForm::kGeneral;
  const Eigen::Matrix4d& A = joint.after.matrix();
  const double c = A(1, 1), s = A(2, 1);
  const bool dh = A(0, 0) == 1.0 && A(1, 0) == 0.0 && A(2, 0) == 0.0 && A(0, 1) == 0.0 &&
                  A(0, 2) == 0.0 && A(1, 2) == -s && A(2, 2) == c && A(1, 3) == 0.0;
  if (!dh) return JointForm::kGeneral;
  if (c == 1.0 && s == 0.0) return JointForm::kDhTwist0;
  if (s == 1.0) return JointForm::kDhTwistPlus90;
  if (s == -1.0) return JointForm::kDhTwistMinus90;
  return JointForm::kDh;
}

std::string numbered_joint_label(int i, const Joint& joint) {
  std::ostringstream s;
  s << "joint " << (i + 1) << " (" << joint.name << ")";
  return s.str();
}

}  // namespace

Result<RobotModel> RobotModel::create(Description d) {
  // Messages name the file when there is one, like the loaders' own messages.
  const std::string where =
      d.source.empty() ? "robot '" + d.name + "'" : "robot file '" + d.source + "'";
  if (d.joints.empty()) return Error{where + ": has no movable joints"};
  for (size_t i = 0; i < d.joints.size(); ++i) {
    Joint& joint = d.joints[i];
    const std::string label = numbered_joint_label(static_cast<int>(i), joint);
    const JointLimits& l = joint.limits;
    if (!joint.before.matrix().allFinite() || !joint.after.matrix().allFinite() ||
        !std::isfinite(joint.offset)) {
      return Error{where + ": " + label + " has a non-finite transform or offset"};
    }
    if (std::isnan(l.lower) || std::isnan(l.upper) || !(l.lower <= l.upper)) {
      return Error{where + ": " + label + " has lower limit " +
                   format_joint_value(joint.type, l.lower) + " above upper limit " +
                   format_joint_value(joint.type, l.upper)};
    }
    if (!(l.max_velocity > 0.0) || !(l.max_acceleration > 0.0) || !std::isfinite(l.max_velocity) ||
        !std::isfinite(l.max_acceleration)) {
      return Error{where + ": " + label + " needs finite, positive max velocity and acceleration"};
    }
    joint.before_is_identity = is_identity_transform(joint.before);
    joint.after_is_identity = is_identity_transform(joint.after);
    joint.form = classify(joint);
  }
  if (!d.T_flange_tool.matrix().allFinite()) {
    return Error{where + ": the tool transform is not finite"};
  }
  for (const NamedConfiguration& c : d.named_configurations) {
    if (c.q.size() != static_cast<Eigen::Index>(d.joints.size())) {
      std::ostringstream s;
      s << where << ": named configuration '" << c.name << "' has " << c.q.size()
        << " values, expected " << d.joints.size();
      return Error{s.str()};
    }
    if (!c.q.allFinite()) {
      return Error{where + ": named configuration '" + c.name + "' is not finite"};
    }
  }
  if (d.dh && d.dh->size() != d.joints.size()) {
    return Error{where + ": DH table and joint list differ in size"};
  }
  return RobotModel(std::move(d));
}

RobotModel::RobotModel(Description description) : d_(std::move(description)) {
  const auto n = static_cast<Eigen::Index>(d_.joints.size());
  lower_.resize(n);
  upper_.resize(n);
  max_velocity_.resize(n);
  max_acceleration_.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const JointLimits& l = d_.joints[static_cast<size_t>(i)].limits;
    lower_[i] = l.lower;
    upper_[i] = l.upper;
    max_velocity_[i] = l.max_velocity;
    max_acceleration_[i] = l.max_acceleration;
  }
}

std::optional<Eigen::VectorXd> RobotModel::named_configuration(const std::string& name) const {
  for (const NamedConfiguration& c : d_.named_configurations) {
    if (c.name == name) return c.q;
  }
  return std::nullopt;
}

Result<RobotModel> RobotModel::with_tool(const Eigen::Isometry3d& T_flange_tool) const {
  Description d = d_;
  d.T_flange_tool = T_flange_tool;
  return create(std::move(d));
}

std::vector<Joint> joints_from_dh(const std::vector<DhRow>& rows,
                                  const std::vector<std::string>& names,
                                  const std::vector<JointLimits>& limits) {
  std::vector<Joint> joints(rows.size());
  for (size_t i = 0; i < rows.size(); ++i) {
    const DhRow& row = rows[i];
    Joint& joint = joints[i];
    joint.name = i < names.size() ? names[i] : "joint" + std::to_string(i + 1);
    joint.type = JointType::kRevolute;
    joint.offset = row.offset;
    joint.after = Eigen::Translation3d(row.a, 0.0, row.d) *
                  Eigen::AngleAxisd(row.alpha, Eigen::Vector3d::UnitX());
    if (i < limits.size()) joint.limits = limits[i];
  }
  return joints;
}

}  // namespace telear::core
