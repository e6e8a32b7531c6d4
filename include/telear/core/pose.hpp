#pragma once
// Rigid transforms. telear uses Eigen::Isometry3d for every pose and names it after the
// frames it relates: T_base_tool is the pose of the tool frame expressed in the base frame,
// so p_base = T_base_tool * p_tool.
//
// Roll-pitch-yaw follows the Robotics Toolbox's rpy2tr default (and ROS / URDF): the rotation
// is R = Rz(yaw) * Ry(pitch) * Rx(roll), i.e. roll about x first, in fixed axes.

#include <Eigen/Geometry>
#include <array>

namespace telear::core {

using Vector6d = Eigen::Matrix<double, 6, 1>;

Eigen::Matrix3d rotation_from_rpy(double roll, double pitch, double yaw);

// Inverse of rotation_from_rpy. At pitch = +-pi/2 (gimbal lock) roll is set to 0 and yaw
// carries the whole rotation about z.
Eigen::Vector3d rpy_from_rotation(const Eigen::Matrix3d& R);

Eigen::Isometry3d pose_from_xyz_rpy(const Eigen::Vector3d& xyz, const Eigen::Vector3d& rpy);

// Rotation vector (axis * angle, angle in [0, pi]) of R; the SO(3) logarithm.
Eigen::Vector3d rotation_vector(const Eigen::Matrix3d& R);

// Rotation matrix of a rotation vector; the SO(3) exponential.
Eigen::Matrix3d rotation_from_vector(const Eigen::Vector3d& rotation_vector);

// 6-vector error [translation; rotation vector] that takes `from` to `to`, both expressed in
// the base frame: applying it as a base-frame twist to `from` yields `to`.
Vector6d pose_error_in_base(const Eigen::Isometry3d& from, const Eigen::Isometry3d& to);

// True when every entry of the 4x4 matrix is finite and its rotation block is orthonormal
// with determinant +1 to within `tolerance`.
bool is_valid_rigid_transform(const Eigen::Matrix4d& T, double tolerance = 1e-6);

// Row-major 4x4 as nested arrays, the layout of telear's JSON output.
std::array<std::array<double, 4>, 4> to_row_major(const Eigen::Isometry3d& T);

}  // namespace telear::core
