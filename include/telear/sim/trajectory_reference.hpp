#pragma once
// A trajectory the simulated robot follows, checked against the robot's own model before it
// is accepted (a rejected one never moves the arm). Two forms come in:
//
// - core's Trajectory: followed exactly, q(t), qd(t) from its trapezoidal time scaling. It was
//   validated when it was created, but perhaps against another model, so its waypoints are
//   validated again and every segment's peak velocity |D_j| s'_max and acceleration
//   |D_j| s''_max are checked against this model's limits.
// - TimedWaypoints (the message form, from an untrusted sender): validated by core's
//   validate_timed_waypoints (finite, within the joint limits, velocity and acceleration as
//   finite differences, starts and ends at rest); followed by linear interpolation between
//   samples, so the velocity is the mean velocity of the current sample interval and changes
//   in steps at the samples, by at most the max acceleration times the mean interval.
//
// Times are seconds from the trajectory's start; before the first and after the last sample
// the arm rests at the first and last joint vector.

#include <Eigen/Core>
#include <variant>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/core/robot_model.hpp"
#include "telear/core/trajectory.hpp"

namespace telear::sim {

class TrajectoryReference {
 public:
  static Result<TrajectoryReference> FromTrajectory(const core::RobotModel& model,
                                                    const core::Trajectory& trajectory);
  static Result<TrajectoryReference> FromTimedWaypoints(const core::RobotModel& model,
                                                        core::TimedWaypoints waypoints);

  double duration() const { return duration_; }
  // The joint vector at t = 0, where the arm must be when the trajectory starts.
  const Eigen::VectorXd& start() const { return start_; }
  // Gripper commands in time order (s from the start).
  const std::vector<core::GripperEvent>& gripper_events() const { return gripper_; }
  // q and qd at time t, clamped to [0, duration()]; outputs resized to the model's dof.
  void sample(double t, Eigen::VectorXd& q, Eigen::VectorXd& qd) const;

 private:
  explicit TrajectoryReference(std::variant<core::Trajectory, core::TimedWaypoints> source);
  std::variant<core::Trajectory, core::TimedWaypoints> source_;
  Eigen::VectorXd start_;
  double duration_ = 0.0;
  std::vector<core::GripperEvent> gripper_;
};

}  // namespace telear::sim
