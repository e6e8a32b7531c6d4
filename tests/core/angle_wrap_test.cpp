// core/angles.hpp: wrap_small_angle, the closed-form IK's fast wrap, agrees with wrap_to_pi on
// (-pi, pi] for angles within a few turns and beyond.

#include <gtest/gtest.h>

#include <numbers>

#include "telear/core/angles.hpp"

namespace telear::core {
namespace {

TEST(WrapSmallAngle, AgreesWithWrapToPi) {
  for (double a = -30.0; a <= 30.0; a += 0.037) {
    EXPECT_DOUBLE_EQ(wrap_small_angle(a), wrap_to_pi(a)) << a;
  }
  EXPECT_DOUBLE_EQ(wrap_small_angle(1000.0), wrap_to_pi(1000.0));  // a huge DH offset
}

TEST(WrapSmallAngle, KeepsPiAndTurnsMinusPiIntoPi) {
  EXPECT_EQ(wrap_small_angle(std::numbers::pi), std::numbers::pi);
  EXPECT_EQ(wrap_small_angle(-std::numbers::pi), std::numbers::pi);
  EXPECT_EQ(wrap_small_angle(0.5), 0.5);
}

}  // namespace
}  // namespace telear::core
