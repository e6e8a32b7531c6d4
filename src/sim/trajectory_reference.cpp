#include "telear/sim/trajectory_reference.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "telear/core/joint_limits.hpp"

namespace telear::sim {
namespace {

// Planned profiles may exceed the limits by this fraction (rounding), as in
// TimedWaypointsLimits::relative_tolerance.
constexpr double kRelativeTolerance = 1e-6;

// Every segment's peak velocity and acceleration within this model's limits.
Status check_profiles(const core::RobotModel& model, const core::Trajectory& trajectory) {
  const auto& waypoints = trajectory.waypoints();
  const auto& profiles = trajectory.segment_profiles();
  const auto& times = trajectory.waypoint_times();
  const double slack = 1.0 + kRelativeTolerance;
  for (size_t k = 0; k < profiles.size(); ++k) {
    const Eigen::VectorXd D = waypoints[k + 1].q - waypoints[k].q;
    const std::string where = "segment waypoint[" + std::to_string(k) + "] to waypoint[" +
                              std::to_string(k + 1) + "] (t = " + core::format_seconds(times[k]) +
                              " to " + core::format_seconds(times[k + 1]) + "): ";
    for (int j = 0; j < model.dof(); ++j) {
      const double v = std::abs(D[j]) * profiles[k].peak_rate;
      const double a = std::abs(D[j]) * profiles[k].acceleration;
      if (v > model.max_velocities()[j] * slack) {
        return Error{where + core::joint_label(model, j) + " moves at " +
                     core::format_joint_value(model, j, v) + "/s, beyond its max velocity of " +
                     core::format_joint_value(model, j, model.max_velocities()[j]) + "/s"};
      }
      if (a > model.max_accelerations()[j] * slack) {
        return Error{where + core::joint_label(model, j) + " accelerates at " +
                     core::format_joint_value(model, j, a) +
                     "/s^2, beyond its max acceleration of " +
                     core::format_joint_value(model, j, model.max_accelerations()[j]) + "/s^2"};
      }
    }
  }
  // Blends around via waypoints accelerate where no segment's trapezoid says: their peaks.
  const Eigen::VectorXd peak = trajectory.peak_accelerations();
  for (int j = 0; j < model.dof(); ++j) {
    if (peak[j] > model.max_accelerations()[j] * slack) {
      return Error{"a blend at a via waypoint: " + core::joint_label(model, j) +
                   " accelerates at " + core::format_joint_value(model, j, peak[j]) +
                   "/s^2, beyond its max acceleration of " +
                   core::format_joint_value(model, j, model.max_accelerations()[j]) + "/s^2"};
    }
  }
  return Status::Ok();
}

}  // namespace

TrajectoryReference::TrajectoryReference(
    std::variant<core::Trajectory, core::TimedWaypoints> source)
    : source_(std::move(source)) {}

Result<TrajectoryReference> TrajectoryReference::FromTrajectory(
    const core::RobotModel& model, const core::Trajectory& trajectory) {
  if (trajectory.dof() != model.dof()) {
    return Error{"the trajectory has " + std::to_string(trajectory.dof()) + " joints, robot '" +
                 model.name() + "' has " + std::to_string(model.dof())};
  }
  if (Status s = core::validate_waypoints(model, trajectory.waypoints()); !s) return s.error();
  if (Status s = check_profiles(model, trajectory); !s) return s.error();
  TrajectoryReference reference(trajectory);
  reference.start_ = trajectory.waypoints().front().q;
  reference.duration_ = trajectory.duration();
  reference.gripper_ = trajectory.gripper_events();
  return reference;
}

Result<TrajectoryReference> TrajectoryReference::FromTimedWaypoints(
    const core::RobotModel& model, core::TimedWaypoints waypoints) {
  if (Status s = core::validate_timed_waypoints(model, waypoints); !s) return s.error();
  Eigen::VectorXd start = waypoints.q.front();
  const double duration = waypoints.times.back();
  std::vector<core::GripperEvent> gripper = waypoints.gripper;
  TrajectoryReference reference(std::move(waypoints));
  reference.start_ = std::move(start);
  reference.duration_ = duration;
  reference.gripper_ = std::move(gripper);
  return reference;
}

void TrajectoryReference::sample(double t, Eigen::VectorXd& q, Eigen::VectorXd& qd) const {
  if (const auto* trajectory = std::get_if<core::Trajectory>(&source_)) {
    trajectory->sample(t, q, &qd);
    return;
  }
  const auto& w = std::get<core::TimedWaypoints>(source_);
  qd.setZero(start_.size());
  if (t <= w.times.front()) {
    q = w.q.front();
    return;
  }
  if (t >= w.times.back()) {
    q = w.q.back();
    return;
  }
  // Interval k with times[k - 1] <= t < times[k].
  const auto next = std::upper_bound(w.times.begin(), w.times.end(), t);
  const auto k = static_cast<size_t>(next - w.times.begin());
  const double h = w.times[k] - w.times[k - 1];
  const double s = (t - w.times[k - 1]) / h;
  qd = (w.q[k] - w.q[k - 1]) / h;
  q = w.q[k - 1] + (w.q[k] - w.q[k - 1]) * s;
}

}  // namespace telear::sim
