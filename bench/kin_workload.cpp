#include "bench/kin_workload.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "telear/core/kinematics.hpp"
#include "telear/core/random_configuration.hpp"

namespace telear::bench {
namespace {

Eigen::VectorXd draw(const core::RobotModel& model, std::mt19937_64& rng) {
  return core::random_configuration(model, rng);
}

}  // namespace

std::vector<Eigen::VectorXd> random_configurations(const core::RobotModel& model, int count,
                                                   std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<Eigen::VectorXd> out;
  out.reserve(static_cast<size_t>(count));
  for (int k = 0; k < count; ++k) out.push_back(draw(model, rng));
  return out;
}

std::vector<IkCase> make_ik_cases(const core::RobotModel& model, int count, std::uint64_t seed,
                                  double seed_noise_rad) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> noise(-seed_noise_rad, seed_noise_rad);
  core::KinematicsData data(model);
  std::vector<IkCase> out;
  out.reserve(static_cast<size_t>(count));
  for (int k = 0; k < count; ++k) {
    IkCase c;
    c.q_true = draw(model, rng);
    core::forward_kinematics(model, data, c.q_true);
    c.T_base_tool = data.T_base_tool;
    c.q_near = c.q_true;
    for (int i = 0; i < model.dof(); ++i) {
      c.q_near[i] =
          std::clamp(c.q_true[i] + noise(rng), model.lower_limits()[i], model.upper_limits()[i]);
    }
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace telear::bench
