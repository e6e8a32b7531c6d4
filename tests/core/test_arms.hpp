#pragma once
// Arms built in code for the IK tests: a UR-type 6-DOF arm (standard DH: the UR class's
// closed form, core/ik_ur.hpp, read from a DH table, and the numeric search's reference arm)
// and a Panda-like 7-DOF arm (modified DH, published joint limits). They are for what a
// robot file cannot vary (a narrowed joint 1, reversed axes); the shipped arms
// (data/robots/ur6.yaml, arm7.yaml: URDFs) are loaded as every command loads them by
// tests/core/ik_ur_test.cpp, shipped_arms_ik_test.cpp and tests/session/ghost_arm_test.cpp.

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "telear/core/robot_model.hpp"

namespace telear::core::test_arms {

inline RobotModel ur_type(double joint1_lower = -2.0 * std::numbers::pi,
                          double joint1_upper = 2.0 * std::numbers::pi) {
  constexpr double kHalf = std::numbers::pi / 2.0;
  const std::vector<DhRow> rows = {{0.089159, 0.0, kHalf, 0.0}, {0.0, -0.425, 0.0, 0.0},
                                   {0.0, -0.39225, 0.0, 0.0},   {0.10915, 0.0, kHalf, 0.0},
                                   {0.09465, 0.0, -kHalf, 0.0}, {0.0823, 0.0, 0.0, 0.0}};
  std::vector<JointLimits> limits(6, {-2.0 * std::numbers::pi, 2.0 * std::numbers::pi, 3.15, 10.0});
  limits[0].lower = joint1_lower;
  limits[0].upper = joint1_upper;
  RobotModel::Description d;
  d.name = "ur_type";
  d.joints = joints_from_dh(
      rows, {"shoulder_pan", "shoulder_lift", "elbow", "wrist_1", "wrist_2", "wrist_3"}, limits);
  d.dh = rows;
  return *RobotModel::create(std::move(d));
}

// Modified DH (Craig): T_{i-1,i} = Rx(alpha_{i-1}) Tx(a_{i-1}) Rz(q_i) Tz(d_i); Tz commutes
// with Rz, so before_i = Rx(alpha_{i-1}) Tx(a_{i-1}) Tz(d_i) and after_i = I (URDF style).
inline RobotModel panda_like() {
  constexpr double kHalf = std::numbers::pi / 2.0;
  struct Row {
    double a, d, alpha;
  };
  const Row rows[7] = {{0.0, 0.333, 0.0},    {0.0, 0.0, -kHalf},       {0.0, 0.316, kHalf},
                       {0.0825, 0.0, kHalf}, {-0.0825, 0.384, -kHalf}, {0.0, 0.0, kHalf},
                       {0.088, 0.0, kHalf}};
  // Published limits: position (rad), velocity (rad/s), acceleration (rad/s^2).
  const JointLimits limits[7] = {{-2.8973, 2.8973, 2.175, 15.0}, {-1.7628, 1.7628, 2.175, 7.5},
                                 {-2.8973, 2.8973, 2.175, 10.0}, {-3.0718, -0.0698, 2.175, 12.5},
                                 {-2.8973, 2.8973, 2.61, 15.0},  {-0.0175, 3.7525, 2.61, 20.0},
                                 {-2.8973, 2.8973, 2.61, 20.0}};
  RobotModel::Description d;
  d.name = "panda_like";
  for (int i = 0; i < 7; ++i) {
    Joint j;
    j.name = "joint" + std::to_string(i + 1);
    j.before = Eigen::AngleAxisd(rows[i].alpha, Eigen::Vector3d::UnitX()) *
               Eigen::Translation3d(rows[i].a, 0.0, rows[i].d);
    j.limits = limits[i];
    d.joints.push_back(j);
  }
  d.T_flange_tool = Eigen::Translation3d(0.0, 0.0, 0.107);
  return *RobotModel::create(std::move(d));
}

// The Panda's "ready" configuration, mid-range: the rest pose of the tests.
inline Eigen::VectorXd panda_ready() {
  Eigen::VectorXd q(7);
  q << 0.0, -0.785398, 0.0, -2.356194, 0.0, 1.570796, 0.785398;
  return q;
}

}  // namespace telear::core::test_arms
