#pragma once
// The simulated robot's test fixture (tests/sim/simulated_robot_test.cpp,
// simulated_robot_trajectory_test.cpp): a robot on a manual clock stepped period by period,
// and a watch on every period's speeds, accelerations and limits.

#include "telear/sim/simulated_robot.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <thread>
#include <vector>

#include "telear/core/angles.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/sim/servo_thread.hpp"
#include "test_util/test_util.hpp"

namespace telear::sim {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kDt = 0.001;  // the default servo period

using test::deg;

// Watches every period's state: speeds against the max velocities, the change of velocity
// over one period against the max accelerations, positions against the limits.
struct MotionWatch {
  explicit MotionWatch(const core::RobotModel& model) : model(model) {}
  void operator()(const core::RobotState& s) {
    for (int j = 0; j < model.dof(); ++j) {
      velocity_ratio = std::max(velocity_ratio, std::abs(s.qd[j]) / model.max_velocities()[j]);
      if (previous_qd.size() != 0) {
        acceleration_ratio = std::max(acceleration_ratio, std::abs(s.qd[j] - previous_qd[j]) /
                                                              (kDt * model.max_accelerations()[j]));
      }
      within_limits =
          within_limits && s.q[j] >= model.lower_limits()[j] && s.q[j] <= model.upper_limits()[j];
    }
    previous_qd = s.qd;
  }
  const core::RobotModel& model;
  Eigen::VectorXd previous_qd;
  double velocity_ratio = 0.0;
  double acceleration_ratio = 0.0;
  bool within_limits = true;
};

class SimulatedRobotTest : public ::testing::Test {
 protected:
  // A start time other than 0, so that a mix-up of robot time and time since start shows.
  static constexpr double kEpoch = 100.0;

  std::unique_ptr<SimulatedRobot> make(SimulatedRobotOptions options = {}) {
    auto robot = SimulatedRobot::create(model, clock, std::move(options));
    EXPECT_TRUE(robot.ok()) << (robot.ok() ? "" : robot.error().message);
    return robot.ok() ? std::move(robot).value() : nullptr;
  }
  std::unique_ptr<SimulatedRobot> make_at(const Eigen::VectorXd& q) {
    SimulatedRobotOptions options;
    options.initial_q = q;
    return make(options);
  }

  // Advances simulated time period by period, updating the robot and handing each state to
  // `each`. The clock is set from a count, not summed, so no rounding accumulates.
  void run_for(SimulatedRobot& robot, double seconds,
               const std::function<void(const core::RobotState&)>& each = nullptr) {
    const double start = clock->now();
    const long periods = std::lround(seconds / kDt);
    for (long k = 1; k <= periods; ++k) {
      clock->set(start + static_cast<double>(k) * kDt);
      robot.update();
      if (each) each(robot.state());
    }
  }

  core::RobotModelPtr model = test::puma560();
  std::shared_ptr<ManualClock> clock = std::make_shared<ManualClock>(kEpoch);
  const Eigen::VectorXd q_start = deg({0, 45, -60, 0, 30, 0});  // away from singularities
};

class SimulatedRobotTrajectoryTest : public SimulatedRobotTest {
 protected:
  core::Trajectory make_trajectory(const Eigen::VectorXd& from) {
    auto trajectory = core::Trajectory::create(
        *model,
        {{from}, {deg({30, 20, -30, 40, 60, 90})}, {deg({-20, 50, -90, -30, 10, 0}), 0.0, 0.0}});
    EXPECT_TRUE(trajectory.ok());
    return std::move(trajectory).value();
  }
};

}  // namespace telear::sim
