#include "telear/core/arm_body_pose.hpp"

#include <algorithm>
#include <cassert>

namespace telear::core {

ArmBodyPose::ArmBodyPose(const RobotModel& model, const ArmBody& body)
    : model_(&model),
      data_(model),
      gripper_(body.gripper),
      gripper_joints_(body.gripper_joints),
      max_opening_(body.max_gripper_opening()) {
  assert(body.dof == model.dof() && "ArmBodyPose: the body was built for another robot");
  for (const BodyPart& part : body.parts) {
    part_link_.push_back(part.link);
    part_finger_side_.push_back(part.finger_side);
    part_steps_.push_back(part.steps);
  }
  T_base_part_.assign(body.parts.size(), Eigen::Matrix4f::Identity());
  opening_ = body.default_gripper_opening();
  forward_kinematics(model, data_, data_.q);
  refresh_parts_from_link(0);
  dirty_first_ = 0;
  dirty_end_ = part_count();
}

void ArmBodyPose::set_configuration(const Eigen::VectorXd& q) {
  update_kinematics(*model_, data_, q);
  if (data_.last_frames_recomputed == 0) return;  // nothing changed
  refresh_parts_from_link(data_.last_first_updated_joint + 1);
}

void ArmBodyPose::set_joint(int joint, double value) {
  assert(joint >= 0 && joint < model_->dof() && "ArmBodyPose::set_joint(): index out of range");
  if (data_.q[joint] == value) return;
  core::set_joint(*model_, data_, joint, value);
  // Joint j (0-based) moves frames j+1..n, i.e. the parts attached to links j+1..n.
  refresh_parts_from_link(joint + 1);
}

void ArmBodyPose::set_gripper_opening(float opening_m) {
  if (!gripper_ && !gripper_joints_) return;
  const float clamped = std::clamp(opening_m, 0.0f, max_opening_);
  if (clamped == opening_) return;
  opening_ = clamped;
  refresh_fingers();
}

PartRange ArmBodyPose::changed() const {
  return {dirty_first_, std::max(0, dirty_end_ - dirty_first_)};
}

void ArmBodyPose::clear_changes() {
  dirty_first_ = 0;
  dirty_end_ = 0;
}

void ArmBodyPose::refresh_parts_from_link(int first_link) {
  int first = part_count(), end = 0;
  for (int k = 0; k < part_count(); ++k) {
    const int link = part_link_[static_cast<std::size_t>(k)];
    if (link < first_link) continue;
    Eigen::Matrix4f& M = T_base_part_[static_cast<std::size_t>(k)];
    M = data_.T_base_link[static_cast<std::size_t>(link)].matrix().cast<float>();
    if (moves_with_opening(k)) M = M * T_link_part(k);
    first = std::min(first, k);
    end = std::max(end, k + 1);
  }
  mark(first, end);
}

void ArmBodyPose::refresh_fingers() {
  int first = part_count(), end = 0;
  for (int k = 0; k < part_count(); ++k) {
    if (!moves_with_opening(k)) continue;
    const int link = part_link_[static_cast<std::size_t>(k)];
    T_base_part_[static_cast<std::size_t>(k)] =
        data_.T_base_link[static_cast<std::size_t>(link)].matrix().cast<float>() * T_link_part(k);
    first = std::min(first, k);
    end = std::max(end, k + 1);
  }
  mark(first, end);
}

bool ArmBodyPose::moves_with_opening(int part) const {
  const auto k = static_cast<std::size_t>(part);
  return (part_finger_side_[k] != 0 && gripper_) || (!part_steps_[k].empty() && gripper_joints_);
}

Eigen::Matrix4f ArmBodyPose::T_link_part(int part) const {
  const auto k = static_cast<std::size_t>(part);
  if (part_finger_side_[k] != 0)
    return T_link_finger(*gripper_, part_finger_side_[k], opening_).matrix();
  return T_link_moving_part(part_steps_[k], *gripper_joints_, opening_).matrix();
}

void ArmBodyPose::mark(int first, int end) {
  if (end <= first) return;
  if (dirty_end_ <= dirty_first_) {
    dirty_first_ = first;
    dirty_end_ = end;
  } else {
    dirty_first_ = std::min(dirty_first_, first);
    dirty_end_ = std::max(dirty_end_, end);
  }
}

}  // namespace telear::core
