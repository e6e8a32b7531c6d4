#pragma once
// Times a numeric IK solver over the shared cases (bench/kin_workload.hpp) and checks each
// answer: FK of it must reach the target and it must lie within the limits modulo whole turns
// (core/joint_limits.hpp). Times are CPU microseconds per solve (bench/cpu_timing.hpp).

#include <algorithm>
#include <cmath>
#include <vector>

#include "bench/cpu_timing.hpp"
#include "bench/kin_workload.hpp"
#include "telear/core/joint_limits.hpp"
#include "telear/core/kinematics.hpp"

namespace telear::bench {

// Outcome of one numeric IK solver over every target. A target counts as solved when the
// solver reports success, forward kinematics of its answer reaches the target (within the
// verification tolerance) and every joint lies within its limits (or a 2 pi equivalent
// does): an answer the arm cannot take is no answer.
struct IkStats {
  double solved_percent = 0.0;
  double mean_us = 0.0;  // over every target, failures included: what a caller pays
  double p99_us = 0.0;
  int outside_limits = 0;  // reported solved, but some joint outside its limits
  int unverified = 0;      // reported solved, but FK of the answer misses the target
};

// Times solve(k) -> (success, q) for every case k, one CPU-clock reading per solve.
template <typename Solve>
IkStats time_numeric_ik(const core::RobotModel& model, const std::vector<IkCase>& cases,
                        Solve&& solve, double verify_position_m, double verify_rotation_rad) {
  std::vector<double> times_us(cases.size());
  int solved = 0;
  IkStats stats;
  core::KinematicsData data(model);
  for (size_t k = 0; k < cases.size(); ++k) {
    const double t0 = cpu_seconds();
    const auto [success, q] = solve(k);
    times_us[k] = (cpu_seconds() - t0) * 1e6;
    if (!success) continue;
    core::forward_kinematics(model, data, q);
    const core::Vector6d e = core::pose_error_in_base(data.T_base_tool, cases[k].T_base_tool);
    if (e.head<3>().norm() > verify_position_m || e.tail<3>().norm() > verify_rotation_rad) {
      ++stats.unverified;
    } else if (!core::within_limits_modulo_turns(model, q)) {
      ++stats.outside_limits;
    } else {
      ++solved;
    }
  }
  const auto count = static_cast<double>(cases.size());
  stats.solved_percent = 100.0 * solved / count;
  double sum = 0.0;
  for (double t : times_us) sum += t;
  stats.mean_us = sum / count;
  const auto p99 = static_cast<size_t>(std::ceil(0.99 * count)) - 1;
  std::nth_element(times_us.begin(), times_us.begin() + static_cast<long>(p99), times_us.end());
  stats.p99_us = times_us[p99];
  return stats;
}

}  // namespace telear::bench
