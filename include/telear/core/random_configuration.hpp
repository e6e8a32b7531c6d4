#pragma once
// Seeded random joint vectors, uniform within a model's limits: the workloads of tests,
// benchmarks, accuracy evaluations and IK restarts all sample the joint space the same way.

#include <Eigen/Core>
#include <random>

#include "telear/core/robot_model.hpp"

namespace telear::core {

// Uniform within [lower, upper] per joint; a joint with an infinite limit (URDF continuous)
// is sampled in [-pi, pi].
Eigen::VectorXd random_configuration(const RobotModel& model, std::mt19937_64& rng);

}  // namespace telear::core
