#include "telear/core/blended_run.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <limits>

namespace telear::core {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Step 2 lengthens by this much more than the exact factor, so that a blend fitting only up
// to rounding does not cost another round.
constexpr double kRepairMargin = 1.0 + 1e-9;

struct Run {
  const std::vector<Eigen::VectorXd>& points;
  const Eigen::VectorXd& v_max;
  const Eigen::VectorXd& a_max;
  std::size_t segments() const { return points.size() - 1; }
  int dof() const { return static_cast<int>(v_max.size()); }
  double displacement(std::size_t s, int j) const { return points[s + 1][j] - points[s][j]; }
};

// Joint j's velocity on segment s of the run timed by T; 0 outside the run (at rest).
double velocity(const Run& run, const std::vector<double>& T, std::ptrdiff_t s, int j) {
  if (s < 0 || s >= static_cast<std::ptrdiff_t>(run.segments())) return 0.0;
  const auto u = static_cast<std::size_t>(s);
  return run.displacement(u, j) / T[u];
}

// b_k: the shortest blend at point k within every joint's acceleration limit.
double needed_blend(const Run& run, const std::vector<double>& T, std::size_t k) {
  double b = 0.0;
  const auto sk = static_cast<std::ptrdiff_t>(k);
  for (int j = 0; j < run.dof(); ++j) {
    const double dv = velocity(run, T, sk, j) - velocity(run, T, sk - 1, j);
    b = std::max(b, std::abs(dv) / run.a_max[j]);
  }
  return b;
}

// The longest blend at point k that takes at most half of either neighbouring segment.
double room(const std::vector<double>& T, std::size_t k) {
  const double before = k == 0 ? kInfinity : T[k - 1];
  const double after = k == T.size() ? kInfinity : T[k];
  return std::min(before, after);
}

// max_j |D_sj| / a_j for segment s, 0 outside the run.
double beta(const Run& run, std::ptrdiff_t s) {
  if (s < 0 || s >= static_cast<std::ptrdiff_t>(run.segments())) return 0.0;
  double b = 0.0;
  for (int j = 0; j < run.dof(); ++j) {
    b = std::max(b, std::abs(run.displacement(static_cast<std::size_t>(s), j)) / run.a_max[j]);
  }
  return b;
}

// The shortest T_s that keeps segment s at least `min_duration` long between its
// waypoints' times. Inside the run that is T_s itself. The first segment starts when the arm leaves
// P_0, half its blend b_0 = beta_0 / T_0 before P_0's nominal time, so its time is T_0 + beta_0 /
// (2 T_0), increasing in T_0 wherever the blend fits (T_0 >= sqrt(beta_0)): the smallest T_0
// reaching min_duration is the larger root of T^2 - md T + beta_0 / 2 = 0 (none: any T_0 will do).
// The same for the last segment, which ends at rest at P_n.
double edge_duration(const Run& run, std::size_t s, double min_duration) {
  if (s != 0 && s + 1 != run.segments()) return min_duration;
  const double half_beta = 0.5 * beta(run, static_cast<std::ptrdiff_t>(s));
  const double discriminant = min_duration * min_duration - 4.0 * half_beta;
  if (discriminant < 0.0) return 0.0;
  return 0.5 * (min_duration + std::sqrt(discriminant));
}

bool all_blends_fit(const Run& run, const std::vector<double>& T) {
  for (std::size_t k = 0; k <= run.segments(); ++k) {
    if (needed_blend(run, T, k) > room(T, k)) return false;
  }
  return true;
}

}  // namespace

BlendedRun time_blended_run(const std::vector<Eigen::VectorXd>& points,
                            const std::vector<double>& min_durations, const Eigen::VectorXd& v_max,
                            const Eigen::VectorXd& a_max) {
  assert(points.size() >= 3 && min_durations.size() + 1 == points.size());
  assert(v_max.size() == a_max.size());
  const Run run{points, v_max, a_max};
  const std::size_t n = run.segments();
  BlendedRun out;
  std::vector<double>& T = out.segment_durations;
  T.resize(n);
  // 1. The slowest joint at full speed, at least the minimum duration.
  for (std::size_t s = 0; s < n; ++s) {
    double alpha = 0.0;
    for (int j = 0; j < run.dof(); ++j) {
      alpha = std::max(alpha, std::abs(run.displacement(s, j)) / v_max[j]);
    }
    T[s] = std::max(alpha, edge_duration(run, s, min_durations[s]));
  }
  // 2. Lengthen the two segments around each corner whose blend does not fit, in point order.
  // A corner depends only on its two segments: one that fitted and whose segments have not
  // changed since still fits, so each round checks only the corners next to a lengthened
  // segment (the same durations as checking every corner, bit for bit; a Cartesian segment's
  // hundreds of via points took ~40 rounds over all of them).
  std::vector<char> unchecked(n + 1, 1);
  for (int round = 0; round < kMaxRepairRounds; ++round) {
    bool changed = false;
    for (std::size_t k = 0; k <= n; ++k) {
      if (!unchecked[k]) continue;
      unchecked[k] = 0;
      const double b = needed_blend(run, T, k);
      const double limit = room(T, k);
      if (b <= limit) continue;
      const double f = std::sqrt(b / limit) * kRepairMargin;
      if (k > 0) T[k - 1] *= f, unchecked[k - 1] = 1;
      if (k < n) T[k] *= f, unchecked[k + 1] = 1;
      unchecked[k] = 1;
      changed = true;
    }
    if (!changed) break;
    ++out.repair_rounds;
  }
  // 3. The bound that fits every blend whatever the neighbours' durations.
  if (!all_blends_fit(run, T)) {
    out.used_fallback = true;
    for (std::size_t s = 0; s < n; ++s) {
      const auto ss = static_cast<std::ptrdiff_t>(s);
      const double b = std::max({beta(run, ss - 1), beta(run, ss), beta(run, ss + 1)});
      T[s] = std::max(T[s], std::sqrt(2.0 * b));
    }
  }
  // 4. Velocities and blends of the final timing.
  out.velocities.resize(n);
  for (std::size_t s = 0; s < n; ++s) {
    out.velocities[s].resize(run.dof());
    for (int j = 0; j < run.dof(); ++j) {
      out.velocities[s][j] = velocity(run, T, static_cast<std::ptrdiff_t>(s), j);
    }
  }
  out.blend_durations.resize(n + 1);
  for (std::size_t k = 0; k <= n; ++k) {
    out.blend_durations[k] = std::min(needed_blend(run, T, k), room(T, k));
  }
  return out;
}

double BlendedRun::duration() const {
  double total = 0.5 * blend_durations.front();
  for (const double T : segment_durations) total += T;
  return total + 0.5 * blend_durations.back();
}

std::size_t sharpest_corner(const std::vector<Eigen::VectorXd>& points,
                            const Eigen::VectorXd& v_max, const Eigen::VectorXd& a_max) {
  assert(points.size() >= 3);
  const Run run{points, v_max, a_max};
  std::vector<double> alpha(run.segments());
  for (std::size_t s = 0; s < run.segments(); ++s) {
    for (int j = 0; j < run.dof(); ++j) {
      alpha[s] = std::max(alpha[s], std::abs(run.displacement(s, j)) / v_max[j]);
    }
  }
  std::size_t sharpest = 1;
  double worst = -1.0;
  for (std::size_t k = 1; k < run.segments(); ++k) {
    const double ratio = needed_blend(run, alpha, k) / room(alpha, k);
    if (ratio > worst) {
      worst = ratio;
      sharpest = k;
    }
  }
  return sharpest;
}

}  // namespace telear::core
