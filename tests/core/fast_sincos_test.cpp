#include "telear/core/fast_sincos.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

namespace telear::core {
namespace {

// Reference values in long double (x87 extended precision on x86-64: 11 more bits than double),
// so that the error of the fast version is measured, not glibc's own half ulp.
long double ref_sin(double x) {
  return std::sin(static_cast<long double>(x));
}
long double ref_cos(double x) {
  return std::cos(static_cast<long double>(x));
}

// Error of `value` in units in the last place of the double nearest `ref`.
double ulp_error(double value, long double ref) {
  const double rounded = static_cast<double>(ref);
  const double ulp = std::nextafter(std::abs(rounded), std::numeric_limits<double>::infinity()) -
                     std::abs(rounded);
  return static_cast<double>(std::abs(static_cast<long double>(value) - ref) / ulp);
}

struct ErrorStats {
  double max_ulp = 0.0;
  double max_abs = 0.0;
  double worst_x = 0.0;
  void add(double x, double value, long double ref) {
    const double u = ulp_error(value, ref);
    if (u > max_ulp) {
      max_ulp = u;
      worst_x = x;
    }
    max_abs = std::max(max_abs, static_cast<double>(std::abs(value - ref)));
  }
};

struct SinCos {
  ErrorStats sin, cos;
};

// Evaluates xs two at a time and collects the errors of both functions.
SinCos measure(const std::vector<double>& xs) {
  std::vector<double> s(xs.size()), c(xs.size());
  sincos_n(xs.data(), s.data(), c.data(), xs.size());
  SinCos e;
  for (size_t i = 0; i < xs.size(); ++i) {
    e.sin.add(xs[i], s[i], ref_sin(xs[i]));
    e.cos.add(xs[i], c[i], ref_cos(xs[i]));
  }
  return e;
}

std::vector<double> uniform(double lo, double hi, int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(lo, hi);
  std::vector<double> xs(static_cast<size_t>(count));
  for (double& x : xs) x = u(rng);
  return xs;
}

TEST(FastSinCos, ReferenceIsExtendedPrecision) {
  // The ulp figures below need a reference more precise than double.
  ASSERT_GE(std::numeric_limits<long double>::digits, 64);
}

TEST(FastSinCos, JointAngleRangeWithinOneAndAHalfUlp) {
  // Every joint angle of a real arm, with offsets: |x| <= 2 pi. Measured: 1.31 ulp (sin),
  // 1.42 ulp (cos); glibc's own double sin / cos are within 1 ulp of this reference.
  const SinCos e = measure(uniform(-2 * std::numbers::pi, 2 * std::numbers::pi, 1'000'000, 1));
  EXPECT_LT(e.sin.max_ulp, 1.5) << "at x = " << e.sin.worst_x;
  EXPECT_LT(e.cos.max_ulp, 1.5) << "at x = " << e.cos.worst_x;
  EXPECT_LT(e.sin.max_abs, 1.2e-16);
  EXPECT_LT(e.cos.max_abs, 1.2e-16);
}

TEST(FastSinCos, WholeFastRangeAbsoluteErrorAndUlp) {
  const SinCos e = measure(uniform(-kFastSinCosMaxArgument, kFastSinCosMaxArgument, 1'000'000, 2));
  // Measured: 1.5e-16 absolute, 2.35 ulp: for large k the reduced argument carries the
  // rounding of two subtractions.
  EXPECT_LT(e.sin.max_abs, 1.7e-16);
  EXPECT_LT(e.cos.max_abs, 1.7e-16);
  EXPECT_LT(e.sin.max_ulp, 2.5) << "at x = " << e.sin.worst_x;
  EXPECT_LT(e.cos.max_ulp, 2.5) << "at x = " << e.cos.worst_x;
}

TEST(FastSinCos, SmallAndTinyArguments) {
  // Log-uniform magnitudes from subnormal to 1, both signs: sin x -> x and cos x -> 1.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> exponent(-1074.0, 0.0);
  std::vector<double> xs;
  for (int i = 0; i < 200'000; ++i) {
    const double x = std::exp2(exponent(rng));
    xs.push_back(i % 2 == 0 ? x : -x);
  }
  const SinCos e = measure(xs);
  EXPECT_LT(e.sin.max_ulp, 1.0) << "at x = " << e.sin.worst_x;
  EXPECT_LT(e.cos.max_ulp, 1.0) << "at x = " << e.cos.worst_x;
}

TEST(FastSinCos, NearMultiplesOfHalfPi) {
  // The double nearest k pi/2 and its neighbours: where one of the results is tiny and
  // x - k p1 - k p2 cancels (exactly: Sterbenz), so the reduced argument stays accurate
  // relative to itself and the tiny result keeps its ulp accuracy.
  std::vector<double> xs;
  for (int k = -64000; k <= 64000; k += 7) {
    const double x = k * (std::numbers::pi / 2);
    if (std::abs(x) > kFastSinCosMaxArgument) continue;
    double y = x;
    for (int step = 0; step < 3; ++step) y = std::nextafter(y, -1e300);
    for (int step = 0; step < 7; ++step, y = std::nextafter(y, 1e300)) xs.push_back(y);
  }
  const SinCos e = measure(xs);
  EXPECT_LT(e.sin.max_abs, 1.7e-16);
  EXPECT_LT(e.cos.max_abs, 1.7e-16);
  EXPECT_LT(e.sin.max_ulp, 2.5) << "at x = " << e.sin.worst_x;
  EXPECT_LT(e.cos.max_ulp, 2.5) << "at x = " << e.cos.worst_x;
}

TEST(FastSinCos, LargeArgumentsFallBackToLibm) {
  // Beyond kFastSinCosMaxArgument the lanes take std::sin / std::cos: bit-identical to them.
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> exponent(std::log2(kFastSinCosMaxArgument), 1023.0);
  std::vector<double> xs = {std::nextafter(kFastSinCosMaxArgument, 1e300),
                            -std::nextafter(kFastSinCosMaxArgument, 1e300),
                            std::numeric_limits<double>::max()};
  for (int i = 0; i < 10'000; ++i) {
    const double x = std::exp2(exponent(rng));
    xs.push_back(i % 2 == 0 ? x : -x);
  }
  std::vector<double> s(xs.size()), c(xs.size());
  sincos_n(xs.data(), s.data(), c.data(), xs.size());
  for (size_t i = 0; i < xs.size(); ++i) {
    if (std::abs(xs[i]) <= kFastSinCosMaxArgument) continue;
    ASSERT_EQ(s[i], std::sin(xs[i])) << "x = " << xs[i];
    ASSERT_EQ(c[i], std::cos(xs[i])) << "x = " << xs[i];
  }
  // The boundary itself is still on the fast path, and accurate.
  const SinCos e = measure({kFastSinCosMaxArgument, -kFastSinCosMaxArgument});
  EXPECT_LT(e.sin.max_ulp, 2.5);
  EXPECT_LT(e.cos.max_ulp, 2.5);
}

TEST(FastSinCos, SpecialValues) {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> xs = {0.0,
                                  -0.0,
                                  inf,
                                  -inf,
                                  nan,
                                  std::numeric_limits<double>::min(),
                                  std::numeric_limits<double>::denorm_min()};
  std::vector<double> s(xs.size()), c(xs.size());
  sincos_n(xs.data(), s.data(), c.data(), xs.size());
  EXPECT_EQ(s[0], 0.0);
  EXPECT_FALSE(std::signbit(s[0]));
  EXPECT_EQ(c[0], 1.0);
  EXPECT_EQ(s[1], 0.0);  // +0, not IEEE's -0: r + (r z) P adds (-0)(-P) = +0 (documented)
  EXPECT_EQ(c[1], 1.0);
  for (size_t i = 2; i <= 4; ++i) {
    EXPECT_TRUE(std::isnan(s[i])) << "x = " << xs[i];
    EXPECT_TRUE(std::isnan(c[i])) << "x = " << xs[i];
  }
  EXPECT_EQ(s[5], xs[5]);
  EXPECT_EQ(c[5], 1.0);
  EXPECT_EQ(s[6], xs[6]);
  EXPECT_EQ(c[6], 1.0);
}

TEST(FastSinCos, LaneDoesNotChangeTheResult) {
  // Incremental forward kinematics pairs a joint with a different partner, in the other lane,
  // than full forward kinematics does: the result must be the same bit for bit.
  const std::vector<double> xs = uniform(-10.0, 10.0, 10'000, 5);
  for (size_t i = 0; i + 1 < xs.size(); i += 2) {
    Double2 s_ab, c_ab, s_ba, c_ba, s_an, c_an;
    sincos2(Double2{xs[i], xs[i + 1]}, s_ab, c_ab);
    sincos2(Double2{xs[i + 1], xs[i]}, s_ba, c_ba);
    // A NaN or out-of-range partner sends its own lane to libm, not this one.
    sincos2(Double2{xs[i], std::numeric_limits<double>::quiet_NaN()}, s_an, c_an);
    ASSERT_EQ(s_ab[0], s_ba[1]);
    ASSERT_EQ(c_ab[0], c_ba[1]);
    ASSERT_EQ(s_ab[1], s_ba[0]);
    ASSERT_EQ(c_ab[1], c_ba[0]);
    ASSERT_EQ(s_ab[0], s_an[0]);
    ASSERT_EQ(c_ab[0], c_an[0]);
  }
}

TEST(FastSinCos, OddCountsAndEmpty) {
  const std::vector<double> xs = {0.5, 1.5, 2.5};
  std::vector<double> s(3, -7.0), c(3, -7.0);
  sincos_n(xs.data(), s.data(), c.data(), 0);
  EXPECT_EQ(s[0], -7.0);
  sincos_n(xs.data(), s.data(), c.data(), 3);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(s[i], std::sin(xs[i]), 2.3e-16);
    EXPECT_NEAR(c[i], std::cos(xs[i]), 2.3e-16);
  }
}

}  // namespace
}  // namespace telear::core
