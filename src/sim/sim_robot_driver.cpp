#include "telear/sim/sim_robot_driver.hpp"

#include <utility>

#include "telear/core/clock.hpp"

namespace telear::sim {

// The robot's clock: seconds on the monotonic clock since epoch_ns.
class SimRobotDriver::MonotonicClock final : public SimClock {
 public:
  MonotonicClock() : epoch_ns_(core::monotonic_ns()) {}
  double now() const override { return to_s(core::monotonic_ns()); }
  double to_s(std::int64_t ns) const { return core::ns_to_s(ns - epoch_ns_); }
  std::int64_t to_ns(double s) const { return epoch_ns_ + core::s_to_ns(s); }

 private:
  std::int64_t epoch_ns_;
};

Result<std::unique_ptr<SimRobotDriver>> SimRobotDriver::create(core::RobotModelPtr model,
                                                               SimRobotDriverOptions options) {
  auto clock = std::make_shared<const MonotonicClock>();
  auto robot = SimulatedRobot::create(std::move(model), clock, std::move(options.robot));
  if (!robot) return Error{"simulated robot: " + robot.error().message};
  return std::unique_ptr<SimRobotDriver>(
      new SimRobotDriver(std::move(clock), std::move(robot).value(), std::move(options.urdf),
                         std::move(options.tip_link)));
}

SimRobotDriver::SimRobotDriver(std::shared_ptr<const MonotonicClock> clock,
                               std::unique_ptr<SimulatedRobot> robot, std::string urdf,
                               std::string tip_link)
    : clock_(std::move(clock)),
      robot_(std::move(robot)),
      urdf_(std::move(urdf)),
      tip_link_(std::move(tip_link)) {
  servo_ = std::make_unique<ServoThread>(*robot_, robot_->options().servo_period);
}

SimRobotDriver::~SimRobotDriver() {
  servo_.reset();  // joins before the robot goes
}

double SimRobotDriver::to_robot_s(std::int64_t server_ns) const {
  return clock_->to_s(server_ns);
}

std::int64_t SimRobotDriver::to_server_ns(double robot_s) const {
  return clock_->to_ns(robot_s);
}

core::DriverSnapshot SimRobotDriver::snapshot() const {
  // update() integrates the periods due, so the snapshot is at most one servo period old
  // whatever the servo thread's phase.
  robot_->update();
  core::DriverSnapshot snapshot{robot_->state(), 0};
  snapshot.capture_ns = to_server_ns(snapshot.state.time);
  return snapshot;
}

std::optional<core::TrajectoryRecord> SimRobotDriver::trajectory_record(
    const std::string& id) const {
  return robot_->trajectory_record(id);
}

Result<core::MotionOutcome> SimRobotDriver::jog(const core::MotionCommand& command,
                                                std::int64_t expires_ns) {
  return robot_->jog(command, to_robot_s(expires_ns));
}

Status SimRobotDriver::jog_velocity(const Eigen::VectorXd& qd, std::int64_t expires_ns) {
  return robot_->jog_velocity(qd, to_robot_s(expires_ns));
}

Result<core::DriverAcceptance> SimRobotDriver::execute(const std::string& id,
                                                       const core::TimedWaypoints& waypoints) {
  auto accepted = robot_->execute(id, waypoints);
  if (!accepted) return accepted.error();
  return core::DriverAcceptance{accepted->duplicate, accepted->record,
                                to_server_ns(accepted->record.accepted_at)};
}

void SimRobotDriver::stop(const std::string& reason) {
  robot_->cancel(reason);
}

Status SimRobotDriver::set_gripper(double opening) {
  return robot_->set_gripper(opening);
}

void SimRobotDriver::estop(const std::string& reason) {
  robot_->estop(reason);
}

Status SimRobotDriver::reset_estop() {
  return robot_->reset_estop();
}

}  // namespace telear::sim
