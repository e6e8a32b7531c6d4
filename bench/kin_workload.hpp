#pragma once
// Inputs shared by the kinematics benchmarks (the Google Benchmark program and
// `telear bench kin`), so that both time the same work: seeded random joint vectors within
// the limits, and inverse-kinematics cases built from them (reachable by construction).

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "telear/core/robot_model.hpp"

namespace telear::bench {

// Uniform random joint vectors within the model's limits (infinite limits: [-pi, pi]).
std::vector<Eigen::VectorXd> random_configurations(const core::RobotModel& model, int count,
                                                   std::uint64_t seed);

struct IkCase {
  Eigen::VectorXd q_true;         // configuration the target was made from
  Eigen::Isometry3d T_base_tool;  // target: FK(q_true)
  Eigen::VectorXd q_near;         // seed near the answer: q_true + uniform noise, in limits
};

// `count` reachable targets; q_near differs from q_true by up to `seed_noise_rad` per joint.
std::vector<IkCase> make_ik_cases(const core::RobotModel& model, int count, std::uint64_t seed,
                                  double seed_noise_rad = 0.1);

}  // namespace telear::bench
