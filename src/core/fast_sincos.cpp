#include "telear/core/fast_sincos.hpp"

namespace telear::core {

void sincos_n(const double* x, double* s, double* c, std::size_t n) {
  std::size_t i = 0;
  for (; i + 2 <= n; i += 2) {
    Double2 xs, ss, cs;
    std::memcpy(&xs, x + i, sizeof xs);
    sincos2(xs, ss, cs);
    std::memcpy(s + i, &ss, sizeof ss);
    std::memcpy(c + i, &cs, sizeof cs);
  }
  if (i < n) {
    // The odd one out takes lane 0; lane 1 computes a discarded sin / cos of 0.
    const Double2 xs = {x[i], 0.0};
    Double2 ss, cs;
    sincos2(xs, ss, cs);
    s[i] = ss[0];
    c[i] = cs[0];
  }
}

}  // namespace telear::core
