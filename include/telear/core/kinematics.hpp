#pragma once
// Forward kinematics and the geometric Jacobian of a serial arm.
//
// KinematicsData is the per-thread workspace: it caches the joint vector it was last
// evaluated at and every link frame, so that changing joint i re-computes only frames
// i..n (the seed paper's reason for keeping one object per link). No function here
// allocates once the data is constructed. The products are hand-written on SIMD lane pairs
// (kinematics.cpp), with the sines and cosines from fast_sincos.hpp; a standard-DH joint
// (JointForm in robot_model.hpp) is applied as Rz(theta) Tz(d) Tx(a) Rx(alpha) directly.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "telear/core/pose.hpp"
#include "telear/core/robot_model.hpp"

namespace telear::core {

using Jacobian = Eigen::Matrix<double, 6, Eigen::Dynamic>;

struct KinematicsData {
  explicit KinematicsData(const RobotModel& model);

  Eigen::VectorXd q;                           // joint vector the frames are valid for
  std::vector<Eigen::Isometry3d> T_base_link;  // n + 1 frames; [0] is the base (identity)
  Eigen::Isometry3d T_base_tool;               // tool centre point
  // Forward kinematics writes the top three rows of these frames only: their bottom rows are
  // (0 0 0 1) from construction on. Joint i's axis and its origin are not stored: they are
  // column z and the origin of T_base_link[i] * before_i (of T_base_link[i] itself for DH
  // joints), derived by geometric_jacobian.
  // 0-based index of the first joint whose frame was re-computed by the last update, and
  // how many link frames it re-computed; tests use these to prove incremental FK.
  int last_first_updated_joint = 0;
  int last_frames_recomputed = 0;
  bool valid = false;  // false until the first full forward_kinematics
};

// Full forward kinematics: every link frame and the tool pose. q.size() must equal dof();
// callers validating untrusted input use check_joint_vector first.
void forward_kinematics(const RobotModel& model, KinematicsData& data, const Eigen::VectorXd& q);

// Sets joint `joint` to `value` and re-computes only frames joint+1..n and the tool.
void set_joint(const RobotModel& model, KinematicsData& data, int joint, double value);

// Re-computes frames from the first joint whose value differs from data.q (bit-exact
// comparison); a no-op when nothing changed. Equivalent to forward_kinematics.
void update_kinematics(const RobotModel& model, KinematicsData& data, const Eigen::VectorXd& q);

enum class JacobianFrame { kBase, kTool };

// Geometric Jacobian J (6 x n) at data's configuration, rows [linear velocity; angular
// velocity] of the tool centre point, expressed in the base frame or in the tool frame.
void geometric_jacobian(const RobotModel& model, const KinematicsData& data, JacobianFrame frame,
                        Jacobian& J);

// Convenience wrappers that allocate a fresh workspace (for the CLI and tests).
Eigen::Isometry3d tool_pose(const RobotModel& model, const Eigen::VectorXd& q);

// Checks an untrusted joint vector: size equals the model's dof and every value is finite.
Status check_joint_vector(const RobotModel& model, const Eigen::VectorXd& q);

}  // namespace telear::core
