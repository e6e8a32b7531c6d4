// The small evaluation helpers of RobotDescription (robot_description.hpp): link lookup, the
// frame -> link transform and the gripper joints' values. The loader lives with the URDF and
// robot-file parsing (the `desc` piece); this file only evaluates the struct.

#include "telear/core/robot_description.hpp"

#include <algorithm>
#include <cassert>

namespace telear::core {

bool RobotLink::moves_with_gripper() const {
  return std::any_of(steps.begin(), steps.end(),
                     [](const AttachmentStep& s) { return s.gripper_joint >= 0; });
}

double GripperJoint::value(double fraction) const {
  return multiplier * (closed + fraction * (open - closed)) + offset;
}

Eigen::Isometry3d GripperJoint::transform(double fraction) const {
  const double v = value(fraction);
  Eigen::Isometry3d Z = Eigen::Isometry3d::Identity();
  if (type == JointType::kPrismatic) {
    Z.translation().z() = v;
  } else {
    Z.linear() = Eigen::AngleAxisd(v, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  }
  return before * Z * after;
}

double Gripper::fraction(double opening_m) const {
  if (!(max_opening_m > 0.0)) return 0.0;
  return std::clamp(opening_m / max_opening_m, 0.0, 1.0);
}

const RobotLink* RobotDescription::link(const std::string& name) const {
  for (const RobotLink& l : links) {
    if (l.name == name) return &l;
  }
  return nullptr;
}

Eigen::Isometry3d RobotDescription::T_frame_link(std::size_t index, double gripper_fraction) const {
  assert(index < links.size() && "RobotDescription::T_frame_link(): link index out of range");
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (const AttachmentStep& step : links[index].steps) {
    if (step.gripper_joint < 0) {
      T = T * step.fixed;
    } else {
      assert(gripper && static_cast<std::size_t>(step.gripper_joint) < gripper->joints.size() &&
             "RobotDescription::T_frame_link(): gripper joint out of range");
      T = T *
          gripper->joints[static_cast<std::size_t>(step.gripper_joint)].transform(gripper_fraction);
    }
  }
  return T;
}

}  // namespace telear::core
