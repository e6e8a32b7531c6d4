#include "telear/core/pose.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <random>

#include "telear/core/angles.hpp"

namespace telear::core {
namespace {

TEST(Pose, RpyIsZyxFixedAxesAndRoundTrips) {
  // Rz(yaw) Ry(pitch) Rx(roll): a pure yaw of 90 deg takes x to y.
  const Eigen::Matrix3d yaw = rotation_from_rpy(0, 0, std::numbers::pi / 2);
  EXPECT_LT((yaw * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(), 1e-15);
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> angle(-3.0, 3.0), pitch(-1.5, 1.5);
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Vector3d rpy(angle(rng), pitch(rng), angle(rng));
    ASSERT_LT((rpy_from_rotation(rotation_from_rpy(rpy.x(), rpy.y(), rpy.z())) - rpy).norm(),
              1e-12);
  }
}

TEST(Pose, RpyAtGimbalLockKeepsTheRotation) {
  const Eigen::Matrix3d R = rotation_from_rpy(0.3, std::numbers::pi / 2, 0.5);
  const Eigen::Vector3d rpy = rpy_from_rotation(R);
  EXPECT_DOUBLE_EQ(rpy.x(), 0.0);
  EXPECT_LT((rotation_from_rpy(rpy.x(), rpy.y(), rpy.z()) - R).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(Pose, RotationVectorIsTheInverseOfItsExponential) {
  std::mt19937_64 rng(2);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int i = 0; i < 1000; ++i) {
    Eigen::Vector3d v(n(rng), n(rng), n(rng));
    if (v.norm() > 3.0) v *= 3.0 / v.norm();
    ASSERT_LT((rotation_vector(rotation_from_vector(v)) - v).norm(), 1e-10);
  }
  EXPECT_EQ(rotation_from_vector(Eigen::Vector3d::Zero()), Eigen::Matrix3d::Identity());
}

TEST(Pose, ValidatesRigidTransforms) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  EXPECT_TRUE(is_valid_rigid_transform(T));
  T(0, 0) = 2.0;
  EXPECT_FALSE(is_valid_rigid_transform(T));
  T = Eigen::Matrix4d::Identity();
  T(0, 3) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(is_valid_rigid_transform(T));
  T = Eigen::Matrix4d::Identity();
  T(0, 0) = -1.0;  // a reflection is orthonormal but not a rotation
  EXPECT_FALSE(is_valid_rigid_transform(T));
}

TEST(Angles, ConvertAndWrap) {
  EXPECT_DOUBLE_EQ(radians_from_degrees(180.0), std::numbers::pi);
  EXPECT_DOUBLE_EQ(degrees_from_radians(std::numbers::pi / 2), 90.0);
  EXPECT_NEAR(wrap_to_pi(3 * std::numbers::pi / 2), -std::numbers::pi / 2, 1e-15);
  EXPECT_DOUBLE_EQ(wrap_to_pi(-std::numbers::pi), std::numbers::pi);
}

}  // namespace
}  // namespace telear::core
