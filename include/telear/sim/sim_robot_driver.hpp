#pragma once
// The default RobotDriver: the simulated robot (telear/sim/simulated_robot.hpp) run in real time by
// a servo thread (telear/sim/servo_thread.hpp).
//
// Time. The robot's clock counts seconds from the driver's epoch, epoch_ns on the monotonic
// clock (telear/core/clock.hpp):  t_robot = (ns - epoch_ns) 1e-9,  ns = epoch_ns + t_robot 1e9.
// Both conversions live here (to_robot_s / to_server_ns), and the robot's clock reads the
// same monotonic clock, so the two never drift apart.

#include <cstdint>
#include <memory>
#include <string>

#include "telear/core/result.hpp"
#include "telear/core/robot_driver.hpp"
#include "telear/sim/servo_thread.hpp"
#include "telear/sim/simulated_robot.hpp"

namespace telear::sim {

struct SimRobotDriverOptions {
  SimulatedRobotOptions robot;  // initial state, servo period, start tolerance, ...
  std::string urdf;             // reported by urdf(); empty: unknown
  std::string tip_link;         // reported by tip_link(); empty: the URDF's single leaf
};

class SimRobotDriver final : public core::RobotDriver {
 public:
  // Starts the servo thread. Fails with the simulated robot's message on invalid options.
  static Result<std::unique_ptr<SimRobotDriver>> create(core::RobotModelPtr model,
                                                        SimRobotDriverOptions options = {});
  ~SimRobotDriver() override;  // stops the servo thread

  const core::RobotModelPtr& model() const override { return robot_->model(); }
  std::string name() const override { return "simulated"; }
  std::string urdf() const override { return urdf_; }
  std::string tip_link() const override { return tip_link_; }
  double start_tolerance() const override { return robot_->options().start_tolerance; }

  core::DriverSnapshot snapshot() const override;
  std::optional<core::TrajectoryRecord> trajectory_record(const std::string& id) const override;
  Result<core::MotionOutcome> jog(const core::MotionCommand& command,
                                  std::int64_t expires_ns) override;
  Status jog_velocity(const Eigen::VectorXd& qd, std::int64_t expires_ns) override;
  Result<core::DriverAcceptance> execute(const std::string& id,
                                         const core::TimedWaypoints& waypoints) override;
  void stop(const std::string& reason) override;
  Status set_gripper(double opening) override;
  void estop(const std::string& reason) override;
  Status reset_estop() override;

  SimulatedRobot& robot() { return *robot_; }  // test hooks (fault injection)

  double to_robot_s(std::int64_t server_ns) const;
  std::int64_t to_server_ns(double robot_s) const;

 private:
  class MonotonicClock;
  SimRobotDriver(std::shared_ptr<const MonotonicClock> clock, std::unique_ptr<SimulatedRobot> robot,
                 std::string urdf, std::string tip_link);

  std::shared_ptr<const MonotonicClock> clock_;
  std::unique_ptr<SimulatedRobot> robot_;
  std::string urdf_;
  std::string tip_link_;
  std::unique_ptr<ServoThread> servo_;
};

}  // namespace telear::sim
