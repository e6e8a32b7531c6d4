// Within limits modulo whole turns (core::equivalent_within_limits): the one check IK answers,
// `telear kin` and `telear bench kin` use. PUMA 560 limits (data/robots/puma560.yaml): waist
// -160..160 deg, elbow -135..135 deg, wrist roll -266..266 deg.

#include "telear/core/joint_limits.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <numbers>

#include "telear/core/angles.hpp"
#include "test_util/test_util.hpp"

namespace telear::core {
namespace {

double deg(double degrees) {
  return radians_from_degrees(degrees);
}

TEST(EquivalentWithinLimits, KeepsAValueAlreadyInside) {
  const auto model = test::puma560();
  const auto v = equivalent_within_limits(*model, 0, deg(100));
  ASSERT_TRUE(v);
  EXPECT_NEAR(*v, deg(100), 1e-12);
}

TEST(EquivalentWithinLimits, MovesByWholeTurnsIntoTheLimits) {
  const auto model = test::puma560();
  // Waist: 180 deg and -180 deg both lie outside -160..160; 210 deg is -150 deg, inside;
  // 200 deg is -160 deg, on the bound (within the tolerance).
  EXPECT_FALSE(equivalent_within_limits(*model, 0, deg(180)));
  const auto inside = equivalent_within_limits(*model, 0, deg(210));
  ASSERT_TRUE(inside);
  EXPECT_NEAR(*inside, deg(-150), 1e-12);
  const auto on_bound = equivalent_within_limits(*model, 0, deg(200), 1e-9);
  ASSERT_TRUE(on_bound);
  EXPECT_NEAR(*on_bound, deg(-160), 1e-9);
  // Wrist roll spans more than a turn: 300 deg -> -60 deg, the lowest equivalent inside.
  const auto wrist = equivalent_within_limits(*model, 3, deg(300) + 4.0 * std::numbers::pi);
  ASSERT_TRUE(wrist);
  EXPECT_NEAR(*wrist, deg(-60), 1e-9);
}

TEST(EquivalentWithinLimits, ReportsTheFirstJointWithNoEquivalent) {
  const auto model = test::puma560();
  Eigen::VectorXd q = Eigen::VectorXd::Zero(6);
  EXPECT_TRUE(within_limits_modulo_turns(*model, q));
  EXPECT_FALSE(first_joint_outside_limits_modulo_turns(*model, q));
  q[0] = deg(-340);  // = 20 deg
  q[2] = deg(180);   // the elbow's -180 / 180 both lie beyond 135
  EXPECT_FALSE(within_limits(*model, q));
  EXPECT_FALSE(within_limits_modulo_turns(*model, q));
  EXPECT_EQ(first_joint_outside_limits_modulo_turns(*model, q), 2);
  q[2] = deg(100);
  EXPECT_TRUE(within_limits_modulo_turns(*model, q));
  q[1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(first_joint_outside_limits_modulo_turns(*model, q), 1);
}

}  // namespace
}  // namespace telear::core
