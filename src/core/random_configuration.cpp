#include "telear/core/random_configuration.hpp"

#include <cmath>
#include <numbers>

namespace telear::core {

Eigen::VectorXd random_configuration(const RobotModel& model, std::mt19937_64& rng) {
  Eigen::VectorXd q(model.dof());
  for (int i = 0; i < model.dof(); ++i) {
    double lo = model.lower_limits()[i];
    double hi = model.upper_limits()[i];
    if (!std::isfinite(lo) || !std::isfinite(hi)) {
      lo = -std::numbers::pi;
      hi = std::numbers::pi;
    }
    q[i] = std::uniform_real_distribution<double>(lo, hi)(rng);
  }
  return q;
}

}  // namespace telear::core
