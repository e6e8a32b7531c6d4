#pragma once
// Sine and cosine of two angles at once, in the two lanes of one SSE2 register.
//
// Forward kinematics of a 6-joint arm needs six sines and six cosines before any frame can be
// formed; six libm sincos calls cost about as much as all the frame products. The angles are
// known up front, so they are evaluated two at a time here, with GCC / Clang vector extensions:
// one SSE2 instruction per operation on baseline x86-64 (NEON on arm64), plain scalar code
// elsewhere. No AVX or FMA is assumed, and ISO C++ mode does not contract a * b + c, so every
// operation is one exactly rounded IEEE operation lane by lane: a lane's result does not depend
// on the other lane or on which lane it was computed in (incremental FK relies on this).
//
// Method (fdlibm's, __kernel_sin / __kernel_cos and the medium-size __ieee754_rem_pio2):
//
//   1. Quadrant: k = round(x * 2/pi), found by adding 1.5 * 2^52, which leaves k in the low
//      mantissa bits (read as an integer for k mod 4) and, subtracted again, k as a double.
//   2. Reduction (Cody-Waite): r = x - k * pi/2 in [-pi/4, pi/4] (slightly beyond where x * 2/pi
//      rounded), with pi/2 split into three parts p1 + p2 + p3. p1 and p2 have 33 significant
//      bits, so k * p1 and k * p2 are exact for |k| < 2^20 and x - k * p1 is exact (Sterbenz);
//      only the last two subtractions round. p1 + p2 + p3 differs from pi/2 by 8.5e-32.
//   3. Kernels: sin r = r + r^3 * S(r^2) and cos r = 1 - r^2/2 + r^4 * C(r^2), with fdlibm's
//      degree-6 minimax polynomials S and C (|error| < 2^-58 on [-pi/4, pi/4]), evaluated in
//      Estrin's form (pairs of terms side by side: half the latency of Horner's rule). The cos
//      kernel adds 1 - r^2/2 as w + ((1 - w) - r^2/2) to keep the rounding error of w.
//   4. Quadrant: sin x = sin r, cos r, -sin r, -cos r for k mod 4 = 0, 1, 2, 3; cos x = cos r,
//      -sin r, -cos r, sin r. Done with bit masks (swap on odd k, flip the sign bit), no branch.
//
// Accuracy, against an extended-precision reference (tests/core/fast_sincos_test.cpp, 1e6
// seeded samples per range): for |x| <= 2 pi within 1.5 ulp and 1.2e-16 absolute; over the
// whole fast range within 2.5 ulp and 1.7e-16 absolute (for large k the reduced r carries the
// rounding of two subtractions). Near multiples of pi/2, where a result is tiny, x - k p1 - k p2
// cancels exactly and the tiny result keeps that ulp accuracy. sin(-0) is +0, not -0.
//
// Range: lanes with |x| > kFastSinCosMaxArgument (well inside |k| < 2^20, where k * p1 stays
// exact), and NaN or infinite lanes, fall back to std::sin / std::cos, so the result is always
// defined and NaN in, NaN out. Joint angles never come near the limit.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace telear::core {

// Two doubles in one 128-bit SIMD register; operators act lane by lane.
using Double2 = double __attribute__((vector_size(16)));

inline constexpr double kFastSinCosMaxArgument = 1e5;

namespace fast_sincos_detail {
using Bits2 = std::uint64_t __attribute__((vector_size(16)));

// Lanes std::sin / std::cos must take: beyond the Cody-Waite range, NaN or infinite.
[[gnu::cold, gnu::noinline]] inline void fall_back(const Double2& x, Double2& s, Double2& c) {
  for (int i = 0; i < 2; ++i) {
    if (!(std::abs(x[i]) <= kFastSinCosMaxArgument)) {
      s[i] = std::sin(x[i]);
      c[i] = std::cos(x[i]);
    }
  }
}
}  // namespace fast_sincos_detail

// s = sin(x) and c = cos(x), lane by lane.
inline void sincos2(const Double2& x, Double2& s, Double2& c) {
  using fast_sincos_detail::Bits2;
  constexpr double kRoundShift = 0x1.8p52;  // adding it rounds to an integer, kept in low bits
  const Double2 shifted = x * 6.36619772367581382433e-01 + kRoundShift;  // x * 2/pi
  const Double2 k = shifted - kRoundShift;
  Bits2 quadrant;
  std::memcpy(&quadrant, &shifted, sizeof quadrant);
  const Double2 r = ((x - k * 1.57079632673412561417e+00) - k * 6.07710050630396597660e-11) -
                    k * 2.02226624879595063154e-21;
  const Double2 z = r * r;
  const Double2 z2 = z * z;
  const Double2 z4 = z2 * z2;
  const Double2 sin_poly = (-1.66666666666666324348e-01 + z * 8.33333333332248946124e-03) +
                           z2 * (-1.98412698298579493134e-04 + z * 2.75573137070700676789e-06) +
                           z4 * (-2.50507602534068634195e-08 + z * 1.58969099521155010221e-10);
  const Double2 sin_r = r + (r * z) * sin_poly;
  const Double2 cos_poly = (4.16666666666666019037e-02 + z * -1.38888888888741095749e-03) +
                           z2 * (2.48015872894767294178e-05 + z * -2.75573143513906633035e-07) +
                           z4 * (2.08757232129817482790e-09 + z * -1.13596475577881948265e-11);
  const Double2 half_z = 0.5 * z;
  const Double2 w = 1.0 - half_z;
  const Double2 cos_r = w + (((1.0 - w) - half_z) + z2 * cos_poly);
  Bits2 sin_bits, cos_bits;
  std::memcpy(&sin_bits, &sin_r, sizeof sin_bits);
  std::memcpy(&cos_bits, &cos_r, sizeof cos_bits);
  const Bits2 swap = -(quadrant & 1);  // all ones on odd quadrants
  const Bits2 s_bits = ((sin_bits & ~swap) | (cos_bits & swap)) ^ ((quadrant & 2) << 62);
  const Bits2 c_bits = ((cos_bits & ~swap) | (sin_bits & swap)) ^ (((quadrant + 1) & 2) << 62);
  std::memcpy(&s, &s_bits, sizeof s);
  std::memcpy(&c, &c_bits, sizeof c);
  // One compare pair for both lanes; NaN compares false and takes the fallback.
  const auto in_range = (x <= kFastSinCosMaxArgument) & (x >= -kFastSinCosMaxArgument);
  if (__builtin_expect(!(in_range[0] && in_range[1]), 0)) fast_sincos_detail::fall_back(x, s, c);
}

// s[i] = sin(x[i]) and c[i] = cos(x[i]) for i < n, two at a time.
void sincos_n(const double* x, double* s, double* c, std::size_t n);

}  // namespace telear::core
