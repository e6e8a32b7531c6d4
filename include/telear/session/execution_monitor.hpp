#pragma once
// Watches the real robot follow an executed plan and decides when to cancel.
//
// The plan is the same Trajectory the session sampled and sent; the robot started it at
// start_time on the robot's clock (seconds), so at robot time t the robot should be at
//
//   q_plan(t) = trajectory.sample(t - start_time)      (clamped to [0, duration])
//
// and each state sample (t, q_real) gives the tracking error e = q_real - q_plan(t) per joint
// (rad or m). When |e_j| exceeds the tolerance on any joint the monitor decides to cancel (the
// session then calls RobotClient::cancel with the message), saying where (plan time, joint) and
// by how much. The decision latches: later samples keep it and do not change the message.
// A sample that is not a valid joint vector (wrong size, NaN) also cancels: the motion can no
// longer be watched.
//
// Where the robot reports its own time into the trajectory (RobotState::trajectory_time, which
// stays 0 while the arm moves to the plan's start), update_at_plan_time() compares against that
// instead, so the time the arm needs to reach the start does not count as error.
//
// A plain value class, not thread-safe.

#include <Eigen/Core>
#include <string>

#include "telear/core/robot_model.hpp"
#include "telear/core/trajectory.hpp"

namespace telear::session {

struct MonitorOptions {
  double tolerance = 0.05;  // rad (revolute) or m (prismatic), per joint, > 0
};

struct TrackingStatus {
  double plan_time = 0.0;      // s into the plan the sample was compared at (clamped)
  double progress = 0.0;       // plan_time / duration in [0, 1] (1 for a zero-length plan)
  bool complete = false;       // the plan's time is over (and it was not cancelled)
  Eigen::VectorXd error;       // q_real - q_plan, per joint (empty for an invalid sample)
  double max_abs_error = 0.0;  // max_j |error_j| of this sample
  int worst_joint = -1;        // 0-based joint of max_abs_error

  // Over all samples so far.
  double max_error_so_far = 0.0;
  int max_error_joint = -1;
  double max_error_plan_time = 0.0;
  double rms_error = 0.0;  // RMS over samples of max_abs_error
  int samples = 0;

  // The robot's own servo command (RobotState::q_commanded) against the same trajectory:
  // 0 up to floating point when the robot runs exactly the trajectory the operator previewed
  // (the plan is the message, docs/trajectory.md). Over all samples that carried one.
  double max_command_deviation = 0.0;
  int command_samples = 0;

  bool cancel = false;  // latched
  std::string cancel_message;
};

class ExecutionMonitor {
 public:
  // `model` must not be null and match the trajectory's dof; options.tolerance must be > 0.
  ExecutionMonitor(core::RobotModelPtr model, core::Trajectory trajectory, double start_time,
                   MonitorOptions options = {});

  const core::Trajectory& trajectory() const { return trajectory_; }
  double start_time() const { return start_time_; }
  // Re-anchors the plan on the robot clock (e.g. from the robot's accepted_at).
  void set_start_time(double start_time) { start_time_ = start_time; }
  const MonitorOptions& options() const { return options_; }

  // A state sample at robot time `robot_time` (s).
  const TrackingStatus& update(double robot_time, const Eigen::VectorXd& q_real);
  // A state sample at `plan_time` s into the trajectory (the robot's own report), with the
  // robot's commanded position when it reports one (empty: none).
  const TrackingStatus& update_at_plan_time(double plan_time, const Eigen::VectorXd& q_real,
                                            const Eigen::VectorXd& q_commanded = {});

  const TrackingStatus& status() const { return status_; }
  bool cancelled() const { return status_.cancel; }
  bool complete() const { return status_.complete; }

 private:
  core::RobotModelPtr model_;
  core::Trajectory trajectory_;
  double start_time_ = 0.0;
  MonitorOptions options_;
  TrackingStatus status_;
  double sum_squares_ = 0.0;
  Eigen::VectorXd q_plan_;
};

}  // namespace telear::session
