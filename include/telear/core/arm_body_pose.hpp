#pragma once
// The pose of every part of an ArmBody: one 4x4 matrix per part, T_base_part, kept up to
// date incrementally. This is the per-frame state of the seed's per-link data structure.
//
// Setting joint j (0-based) re-computes only frames j+1..n (core's set_joint /
// update_kinematics) and the matrices of the parts attached to those frames; the range of
// parts whose matrix changed since the last clear_changes() is kept so that the renderer
// uploads only those matrices. Vertices are never touched.
//
// Matrices are float, column-major (Eigen's default), i.e. exactly GL's mat4 layout:
//   T_base_part[k] = T_base_link[parts[k].link] * T_link_part(k, opening).

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "telear/core/arm_body.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/robot_model.hpp"

namespace telear::core {

// A half-open range [first, first + count) of part indices.
struct PartRange {
  int first = 0;
  int count = 0;
  bool empty() const { return count == 0; }
  int end() const { return first + count; }
  bool contains(int part) const { return part >= first && part < end(); }
};

class ArmBodyPose {
 public:
  // Starts at q = 0 and the gripper's default opening; every part is marked changed.
  // The model must outlive this object and match body.dof.
  ArmBodyPose(const RobotModel& model, const ArmBody& body);

  // Incremental: re-computes from the first joint whose value differs (bit-exact).
  void set_configuration(const Eigen::VectorXd& q);
  // Sets one joint (0-based) and re-computes frames joint+1..n.
  void set_joint(int joint, double value);
  // Clamped to [0, max opening]; moves only the parts that move with the opening (fingers,
  // moving parts): their matrices, never their vertices. No-op without a gripper.
  void set_gripper_opening(float opening_m);

  const KinematicsData& kinematics() const { return data_; }
  const Eigen::VectorXd& q() const { return data_.q; }
  float gripper_opening() const { return opening_; }
  int part_count() const { return static_cast<int>(T_base_part_.size()); }
  const std::vector<Eigen::Matrix4f>& T_base_part() const { return T_base_part_; }
  const Eigen::Matrix4f& T_base_part(int part) const {
    return T_base_part_[static_cast<std::size_t>(part)];
  }

  // The smallest contiguous range holding every part whose matrix changed since the last
  // clear_changes() (empty when nothing changed).
  PartRange changed() const;
  void clear_changes();

 private:
  void refresh_parts_from_link(int first_link);
  void refresh_fingers();
  void mark(int first, int end);
  bool moves_with_opening(int part) const;
  Eigen::Matrix4f T_link_part(int part) const;

  const RobotModel* model_;
  KinematicsData data_;
  std::vector<int> part_link_;
  std::vector<int> part_finger_side_;
  std::vector<std::vector<AttachmentStep>> part_steps_;
  std::vector<Eigen::Matrix4f> T_base_part_;
  std::optional<GripperSpec> gripper_;
  std::optional<Gripper> gripper_joints_;
  float max_opening_ = 0.0f;
  float opening_ = 0.0f;
  int dirty_first_ = 0;
  int dirty_end_ = 0;
};

}  // namespace telear::core
