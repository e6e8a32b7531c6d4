#pragma once
// Shared helpers of the test suite: model loading, seeded random configurations, and an
// independent standard-DH product to check kinematics against.

#include <Eigen/Geometry>
#include <initializer_list>
#include <numbers>
#include <random>
#include <string>

#include "telear/core/robot_description.hpp"
#include "telear/core/robot_model.hpp"

namespace telear::test {

// data/ of the source tree.
std::string data_path(const std::string& relative);

// The shipped PUMA 560 (DH YAML); fails the test on error.
core::RobotModelPtr puma560();

// A robot's description (a shipped name or a file), as every command loads it; fails the
// test on error.
core::RobotDescription robot_description(const std::string& robot);

// Uniform random joint vector within the model's limits (infinite limits: [-pi, pi]).
Eigen::VectorXd random_configuration(const core::RobotModel& model, std::mt19937_64& rng);

// Naive 4x4 product of standard DH matrices, written independently of core/kinematics.
Eigen::Matrix4d dh_product(const std::vector<core::DhRow>& rows, const Eigen::VectorXd& q);

inline constexpr double kPi = std::numbers::pi;

// A joint vector from degrees, as configurations read in a manual.
Eigen::VectorXd deg(std::initializer_list<double> values);

// A six-joint vector in radians.
Eigen::VectorXd q6(double a, double b, double c, double d, double e, double f);

// Maximum absolute entry difference of two 4x4 matrices.
double max_abs_diff(const Eigen::Matrix4d& a, const Eigen::Matrix4d& b);

}  // namespace telear::test
