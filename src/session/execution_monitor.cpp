#include "telear/session/execution_monitor.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <utility>

#include "telear/core/angles.hpp"
#include "telear/core/joint_limits.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/number_format.hpp"

#include "seconds.hpp"

namespace telear::session {
namespace {

std::string amount(const core::RobotModel& model, int joint, double value) {
  if (model.joint(joint).type == core::JointType::kRevolute) {
    return core::format_fixed(value, 3, "rad") + " (" +
           core::format_fixed(core::degrees_from_radians(value), 1, "deg") + ")";
  }
  return core::format_fixed(value, 4, "m") + " (" + core::format_fixed(value * 1000.0, 1, "mm") +
         ")";
}

}  // namespace

ExecutionMonitor::ExecutionMonitor(core::RobotModelPtr model, core::Trajectory trajectory,
                                   double start_time, MonitorOptions options)
    : model_(std::move(model)),
      trajectory_(std::move(trajectory)),
      start_time_(start_time),
      options_(options) {
  assert(model_ && model_->dof() == trajectory_.dof() &&
         "ExecutionMonitor: model missing or of another dof than the trajectory");
  assert(options_.tolerance > 0.0 && "ExecutionMonitor: tolerance must be positive");
}

const TrackingStatus& ExecutionMonitor::update(double robot_time, const Eigen::VectorXd& q_real) {
  return update_at_plan_time(robot_time - start_time_, q_real);
}

const TrackingStatus& ExecutionMonitor::update_at_plan_time(double plan_time,
                                                            const Eigen::VectorXd& q_real,
                                                            const Eigen::VectorXd& q_commanded) {
  TrackingStatus& s = status_;
  const double duration = trajectory_.duration();
  const double t = std::isfinite(plan_time) ? std::clamp(plan_time, 0.0, duration) : 0.0;
  s.plan_time = t;
  s.progress = duration > 0.0 ? t / duration : 1.0;
  if (s.cancel) return s;  // latched: the decision and its message stay

  if (Status valid = core::check_joint_vector(*model_, q_real);
      !valid || !std::isfinite(plan_time)) {
    s.error.resize(0);
    s.max_abs_error = 0.0;
    s.worst_joint = -1;
    s.cancel = true;
    s.cancel_message = "execution monitor: the robot reported an invalid state (" +
                       (valid ? std::string("time not finite") : valid.error().message) +
                       "); cancelling";
    return s;
  }
  trajectory_.sample(t, q_plan_);
  if (q_commanded.size() == q_plan_.size() && q_commanded.allFinite()) {
    s.max_command_deviation =
        std::max(s.max_command_deviation, (q_commanded - q_plan_).cwiseAbs().maxCoeff());
    ++s.command_samples;
  }
  s.error = q_real - q_plan_;
  Eigen::Index worst = 0;
  s.max_abs_error = s.error.cwiseAbs().maxCoeff(&worst);
  s.worst_joint = static_cast<int>(worst);
  ++s.samples;
  sum_squares_ += s.max_abs_error * s.max_abs_error;
  s.rms_error = std::sqrt(sum_squares_ / s.samples);
  if (s.max_abs_error > s.max_error_so_far || s.max_error_joint < 0) {
    s.max_error_so_far = s.max_abs_error;
    s.max_error_joint = s.worst_joint;
    s.max_error_plan_time = t;
  }
  if (s.max_abs_error > options_.tolerance) {
    const int j = s.worst_joint;
    s.cancel = true;
    s.complete = false;
    s.cancel_message =
        "execution monitor: at " + seconds(t) + " of " + seconds(duration) + " into the plan, " +
        core::joint_label(*model_, j) + " is " + amount(*model_, j, s.max_abs_error) +
        " from the plan (real " + core::format_joint_value(*model_, j, q_real[j]) + ", plan " +
        core::format_joint_value(*model_, j, q_plan_[j]) + "), beyond the tolerance of " +
        amount(*model_, j, options_.tolerance) + "; cancelling";
    return s;
  }
  s.complete = t >= duration;
  return s;
}

}  // namespace telear::session
