#include "telear/core/pose.hpp"

#include <cmath>
#include <numbers>

namespace telear::core {

Eigen::Matrix3d rotation_from_rpy(double roll, double pitch, double yaw) {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

Eigen::Vector3d rpy_from_rotation(const Eigen::Matrix3d& R) {
  // R(2,0) = -sin(pitch). Near +-1 the roll and yaw axes align.
  const double sin_pitch = -R(2, 0);
  if (std::abs(sin_pitch) > 1.0 - 1e-12) {
    const double pitch = std::copysign(std::numbers::pi / 2.0, sin_pitch);
    const double yaw = std::atan2(-R(0, 1), R(1, 1));
    return {0.0, pitch, yaw};
  }
  const double roll = std::atan2(R(2, 1), R(2, 2));
  const double pitch = std::atan2(sin_pitch, std::hypot(R(2, 1), R(2, 2)));
  const double yaw = std::atan2(R(1, 0), R(0, 0));
  return {roll, pitch, yaw};
}

Eigen::Isometry3d pose_from_xyz_rpy(const Eigen::Vector3d& xyz, const Eigen::Vector3d& rpy) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = rotation_from_rpy(rpy.x(), rpy.y(), rpy.z());
  T.translation() = xyz;
  return T;
}

Eigen::Vector3d rotation_vector(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.axis() * aa.angle();
}

Eigen::Matrix3d rotation_from_vector(const Eigen::Vector3d& v) {
  const double angle = v.norm();
  if (angle < 1e-300) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, v / angle).toRotationMatrix();
}

Vector6d pose_error_in_base(const Eigen::Isometry3d& from, const Eigen::Isometry3d& to) {
  Vector6d e;
  e.head<3>() = to.translation() - from.translation();
  e.tail<3>() = rotation_vector(to.linear() * from.linear().transpose());
  return e;
}

bool is_valid_rigid_transform(const Eigen::Matrix4d& T, double tolerance) {
  if (!T.allFinite()) return false;
  if ((T.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > tolerance) return false;
  const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
  if ((R * R.transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > tolerance) {
    return false;
  }
  return std::abs(R.determinant() - 1.0) <= tolerance;
}

std::array<std::array<double, 4>, 4> to_row_major(const Eigen::Isometry3d& T) {
  std::array<std::array<double, 4>, 4> rows{};
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) rows[r][c] = T.matrix()(r, c);
  }
  return rows;
}

}  // namespace telear::core
