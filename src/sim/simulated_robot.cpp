#include "telear/sim/simulated_robot.hpp"

#include "telear/core/number_format.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "telear/core/joint_limits.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/sim/true_model.hpp"

namespace telear::sim {
namespace {

// Slack when comparing the clock with the servo grid t0 + k dt (s): a ManualClock advanced in
// steps of dt accumulates rounding, and the period it lands on must still count as due.
constexpr double kTimeEpsilon = 1e-9;

bool is_printable_ascii(const std::string& text) {
  return std::all_of(text.begin(), text.end(), [](char c) { return c >= 0x20 && c <= 0x7e; });
}

const char* mode_activity(core::RobotMode mode) {
  switch (mode) {
    case core::RobotMode::kJogging:
      return "jogging";
    case core::RobotMode::kStopping:
      return "stopping";
    case core::RobotMode::kTrajectory:
      return "running a trajectory";
    case core::RobotMode::kEStopped:
      return "e-stopped";
    case core::RobotMode::kIdle:
      break;
  }
  return "idle";
}

Status check_options(const core::RobotModel& model, const SimulatedRobotOptions& o) {
  if (!(std::isfinite(o.servo_period) && o.servo_period > 0.0 && o.servo_period <= 0.1)) {
    return Error{"servo_period must be in (0, 0.1] s, got " + core::format_number(o.servo_period)};
  }
  if (!(std::isfinite(o.gripper_speed) && o.gripper_speed > 0.0)) {
    return Error{"gripper_speed must be a positive finite number (opening per second), got " +
                 core::format_number(o.gripper_speed)};
  }
  if (!(std::isfinite(o.initial_gripper) && o.initial_gripper >= 0.0 && o.initial_gripper <= 1.0)) {
    return Error{"initial_gripper must be in [0, 1] (0 closed, 1 open), got " +
                 core::format_number(o.initial_gripper)};
  }
  if (!(std::isfinite(o.start_tolerance) && o.start_tolerance >= 0.0)) {
    return Error{"start_tolerance must be a non-negative finite number, got " +
                 core::format_number(o.start_tolerance)};
  }
  if (!(std::isfinite(o.stop_deceleration_scale) && o.stop_deceleration_scale > 0.0 &&
        o.stop_deceleration_scale <= 1.0)) {
    return Error{"stop_deceleration_scale must be in (0, 1], got " +
                 core::format_number(o.stop_deceleration_scale)};
  }
  if (!(std::isfinite(o.max_jog_duration) && o.max_jog_duration > 0.0)) {
    return Error{"max_jog_duration must be a positive finite number of seconds, got " +
                 core::format_number(o.max_jog_duration)};
  }
  if (o.max_trajectory_id_length < 1) {
    return Error{"max_trajectory_id_length must be at least 1"};
  }
  if (!(std::isfinite(o.limit_fault_tolerance) && o.limit_fault_tolerance >= 0.0)) {
    return Error{"limit_fault_tolerance must be a non-negative finite number, got " +
                 core::format_number(o.limit_fault_tolerance)};
  }
  if (o.initial_q.size() != 0) {
    if (Status s = core::check_joint_vector(model, o.initial_q); !s) {
      return Error{"initial_q: " + s.error().message};
    }
    if (const auto violation = core::first_limit_violation(model, o.initial_q)) {
      return Error{"initial_q: " + core::describe_violation(model, *violation)};
    }
  }
  return Status::Ok();
}

}  // namespace

// [SECTION] Construction

Result<std::unique_ptr<SimulatedRobot>> SimulatedRobot::create(
    core::RobotModelPtr model, std::shared_ptr<const SimClock> clock,
    SimulatedRobotOptions options) {
  assert(model && clock && "SimulatedRobot::create(): model and clock are required");
  if (Status s = check_options(*model, options); !s) {
    return Error{"simulated robot options: " + s.error().message};
  }
  core::RobotModelPtr true_model = model;
  if (options.true_joint_offsets.size() != 0) {
    auto offset_model = with_joint_offsets(*model, options.true_joint_offsets);
    if (!offset_model) return Error{"simulated robot options: " + offset_model.error().message};
    true_model = std::make_shared<const core::RobotModel>(std::move(offset_model).value());
  }
  return std::unique_ptr<SimulatedRobot>(
      new SimulatedRobot(std::move(model), std::move(true_model), std::move(clock), options));
}

SimulatedRobot::SimulatedRobot(core::RobotModelPtr model, core::RobotModelPtr true_model,
                               std::shared_ptr<const SimClock> clock, SimulatedRobotOptions options)
    : model_(std::move(model)),
      true_model_(std::move(true_model)),
      clock_(std::move(clock)),
      options_(std::move(options)) {
  const int n = model_->dof();
  for (int j = 0; j < n; ++j) {
    const core::JointLimits& l = model_->joint(j).limits;
    limits_.push_back({l.lower, l.upper, l.max_velocity, l.max_acceleration});
  }
  t0_ = clock_->now();
  if (options_.initial_q.size() != 0) {
    q_ = options_.initial_q;
  } else {
    q_ = Eigen::VectorXd::Zero(n).cwiseMax(model_->lower_limits()).cwiseMin(model_->upper_limits());
  }
  q_cmd_ = q_;
  qd_ = qd_cmd_ = Eigen::VectorXd::Zero(n);
  jog_velocity_ = jog_target_ = stop_deceleration_ = Eigen::VectorXd::Zero(n);
  sample_q_ = sample_qd_ = Eigen::VectorXd::Zero(n);
  gripper_ = gripper_target_ = options_.initial_gripper;
  faults_.resize(static_cast<size_t>(n));
  drift_offset_ = Eigen::VectorXd::Zero(n);
}

// [SECTION] Time and state

double SimulatedRobot::now() const {
  return t0_ + static_cast<double>(steps_) * options_.servo_period;
}

void SimulatedRobot::catch_up() {
  const double target = clock_->now();
  while (t0_ + static_cast<double>(steps_ + 1) * options_.servo_period <= target + kTimeEpsilon) {
    step();
  }
}

void SimulatedRobot::update() {
  std::lock_guard lock(mutex_);
  catch_up();
}

double SimulatedRobot::time() const {
  std::lock_guard lock(mutex_);
  return now();
}

core::RobotState SimulatedRobot::state() const {
  std::lock_guard lock(mutex_);
  core::RobotState s;
  s.time = now();
  s.mode = mode_;
  s.q = q_;
  s.qd = qd_;
  s.q_commanded = q_cmd_;
  s.qd_commanded = qd_cmd_;
  s.gripper = gripper_;
  s.gripper_target = gripper_target_;
  s.gripper_moving = gripper_ != gripper_target_;
  s.estop = mode_ == core::RobotMode::kEStopped;
  s.estop_reason = estop_reason_;
  s.estop_time = estop_time_;
  if (trajectory_) {
    s.trajectory_id = trajectory_->id;
    s.trajectory_duration = trajectory_->reference.duration();
    if (!trajectory_->approaching) {
      s.trajectory_time = std::clamp(now() - trajectory_->start_time, 0.0, s.trajectory_duration);
    }
    s.trajectory_progress =
        s.trajectory_duration > 0.0 ? s.trajectory_time / s.trajectory_duration : 0.0;
  }
  if (mode_ == core::RobotMode::kJogging) s.jog_expires_at = jog_expires_at_;
  if (mode_ == core::RobotMode::kStopping) s.stop_reason = stop_reason_;
  s.fault = fault_;
  return s;
}

std::optional<core::TrajectoryRecord> SimulatedRobot::trajectory_record(
    const std::string& id) const {
  std::lock_guard lock(mutex_);
  const auto it = records_.find(id);
  if (it == records_.end()) return std::nullopt;
  return it->second;
}

// [SECTION] The servo period

void SimulatedRobot::step() {
  const double dt = options_.servo_period;
  const double t = now();
  const int n = model_->dof();
  if (mode_ == core::RobotMode::kJogging && t >= jog_expires_at_) {
    begin_stop("the jog expired at t = " + core::format_seconds(jog_expires_at_),
               core::TrajectoryStatus::kCancelled);
  }
  switch (mode_) {
    case core::RobotMode::kIdle:
    case core::RobotMode::kEStopped:
      qd_cmd_.setZero();
      break;
    case core::RobotMode::kJogging: {
      bool all_arrived = true;
      for (int j = 0; j < n; ++j) {
        JointMotion m;
        if (jog_kind_ == JogKind::kVelocity) {
          m = step_velocity(commanded(j), jog_velocity_[j], limits_[j].max_acceleration, limits_[j],
                            dt);
        } else {
          m = step_toward(commanded(j), jog_target_[j], limits_[j], dt);
          all_arrived = all_arrived && arrived(m, jog_target_[j]);
        }
        q_cmd_[j] = m.q;
        qd_cmd_[j] = m.qd;
      }
      if (jog_kind_ == JogKind::kTarget && all_arrived) mode_ = core::RobotMode::kIdle;
      break;
    }
    case core::RobotMode::kTrajectory:
      step_trajectory(t + dt);
      break;
    case core::RobotMode::kStopping: {
      bool at_rest = true;
      for (int j = 0; j < n; ++j) {
        const JointMotion m =
            step_velocity(commanded(j), 0.0, stop_deceleration_[j], limits_[j], dt);
        q_cmd_[j] = m.q;
        qd_cmd_[j] = m.qd;
        at_rest = at_rest && m.qd == 0.0;
      }
      if (at_rest) {
        mode_ = core::RobotMode::kIdle;
        stop_reason_.clear();
      }
      break;
    }
  }
  if (mode_ != core::RobotMode::kEStopped && gripper_ != gripper_target_) {
    const double max_step = options_.gripper_speed * dt;
    gripper_ += std::clamp(gripper_target_ - gripper_, -max_step, max_step);
  }
  ++steps_;
  update_measured(dt);
}

void SimulatedRobot::step_trajectory(double t_next) {
  ActiveTrajectory& active = *trajectory_;
  const Eigen::VectorXd& start = active.reference.start();
  if (active.approaching) {
    bool all_arrived = true;
    for (int j = 0; j < model_->dof(); ++j) {
      const JointMotion m = step_toward(commanded(j), start[j], limits_[j], options_.servo_period);
      q_cmd_[j] = m.q;
      qd_cmd_[j] = m.qd;
      all_arrived = all_arrived && arrived(m, start[j]);
    }
    if (all_arrived) {
      active.approaching = false;
      active.start_time = t_next;
      apply_gripper_events(0.0);
    }
    return;
  }
  const double tau = t_next - active.start_time;
  active.reference.sample(tau, sample_q_, sample_qd_);
  q_cmd_ = sample_q_;
  qd_cmd_ = sample_qd_;
  apply_gripper_events(tau);
  if (tau >= active.reference.duration()) {
    qd_cmd_.setZero();
    finish_trajectory(core::TrajectoryStatus::kCompleted, "");
    mode_ = core::RobotMode::kIdle;
  }
}

void SimulatedRobot::apply_gripper_events(double trajectory_time) {
  ActiveTrajectory& active = *trajectory_;
  const auto& events = active.reference.gripper_events();
  while (active.next_gripper_event < events.size() &&
         events[active.next_gripper_event].time <= trajectory_time + kTimeEpsilon) {
    gripper_target_ = events[active.next_gripper_event].opening;
    ++active.next_gripper_event;
  }
}

void SimulatedRobot::update_measured(double dt) {
  const bool braked = mode_ == core::RobotMode::kEStopped;
  bool clamped = false;  // beyond a limit by more than the tolerance
  for (int j = 0; j < model_->dof(); ++j) {
    JointMotion m{q_[j], qd_[j]};
    const auto& fault = faults_[static_cast<size_t>(j)];
    if (fault) {
      m = apply_joint_fault(*fault, m, commanded(j), braked, drift_offset_[j], dt);
    } else {
      m = braked ? JointMotion{q_[j], 0.0} : commanded(j);
    }
    // The hard clamp, the last line of defence: only a fault gets a joint beyond a limit by
    // more than rounding.
    const JointStepLimits& l = limits_[j];
    if (m.q > l.upper || m.q < l.lower) {
      const bool upper = m.q > l.upper;
      const double bound = upper ? l.upper : l.lower;
      if (std::abs(m.q - bound) > options_.limit_fault_tolerance) {
        clamped = true;
        m.qd = 0.0;
        if (!fault_) {
          fault_ = core::joint_label(*model_, j) + " measured at " +
                   core::format_joint_value(*model_, j, m.q) + ", beyond its " +
                   (upper ? "upper" : "lower") + " limit of " +
                   core::format_joint_value(*model_, j, bound) +
                   ": hard-clamped to the limit at t = " + core::format_seconds(now());
        }
      }
      m.q = bound;
    }
    q_[j] = m.q;
    qd_[j] = m.qd;
  }
  if (clamped && (mode_ == core::RobotMode::kJogging || mode_ == core::RobotMode::kTrajectory)) {
    gripper_target_ = gripper_;
    begin_stop("joint-limit fault: " + fault_.value_or("a joint was clamped at its limit"),
               core::TrajectoryStatus::kAborted);
  }
}

// [SECTION] Stops and records

void SimulatedRobot::begin_stop(const std::string& reason,
                                core::TrajectoryStatus trajectory_status) {
  if (mode_ == core::RobotMode::kIdle || mode_ == core::RobotMode::kEStopped) return;
  if (trajectory_) finish_trajectory(trajectory_status, reason);
  jog_expires_at_ = 0.0;
  const double scale = options_.stop_deceleration_scale;
  const double T = stopping_time(qd_cmd_, model_->max_accelerations(), scale);
  if (T == 0.0) {
    mode_ = core::RobotMode::kIdle;
    stop_reason_.clear();
    return;
  }
  for (int j = 0; j < model_->dof(); ++j) {
    const double a_max = scale * model_->max_accelerations()[j];
    stop_deceleration_[j] = std::min(std::abs(qd_cmd_[j]) / T, a_max);
  }
  stop_reason_ = reason;
  mode_ = core::RobotMode::kStopping;
}

void SimulatedRobot::finish_trajectory(core::TrajectoryStatus status, const std::string& message) {
  core::TrajectoryRecord& record = records_.at(trajectory_->id);
  record.status = status;
  record.finished_at = now();
  record.message = message;
  trajectory_.reset();
}

void SimulatedRobot::sync_command_to_measured() {
  q_cmd_ = q_;
  qd_cmd_.setZero();
  qd_.setZero();
  drift_offset_.setZero();
}

// [SECTION] Commands

Status SimulatedRobot::check_can_move(const char* what) const {
  if (mode_ == core::RobotMode::kEStopped) {
    return Error{std::string(what) + " rejected: the e-stop is engaged (since t = " +
                 core::format_seconds(estop_time_) + ": " + estop_reason_ +
                 "); reset it once the arm is at rest"};
  }
  if (trajectory_) {
    return Error{std::string(what) + " rejected: trajectory '" + trajectory_->id +
                 "' is running; cancel it first or wait until it completes"};
  }
  return Status::Ok();
}

Status SimulatedRobot::check_jog_expiry(double expires_at) const {
  const double t = now();
  if (!std::isfinite(expires_at)) {
    return Error{"jog rejected: its expiry time is not a finite number: " +
                 core::format_number(expires_at)};
  }
  if (expires_at <= t) {
    return Error{"jog ignored: it expired at t = " + core::format_seconds(expires_at) + ", " +
                 core::format_seconds(t - expires_at) +
                 " before it arrived at t = " + core::format_seconds(t)};
  }
  if (expires_at - t > options_.max_jog_duration) {
    return Error{"jog rejected: it expires " + core::format_seconds(expires_at - t) +
                 " from now, later than the maximum of " +
                 core::format_seconds(options_.max_jog_duration)};
  }
  return Status::Ok();
}

Status SimulatedRobot::jog_velocity(const Eigen::VectorXd& qd, double expires_at) {
  std::lock_guard lock(mutex_);
  catch_up();
  if (Status s = check_can_move("jog"); !s) return s;
  if (Status s = check_jog_expiry(expires_at); !s) return s;
  if (Status s = core::check_joint_vector(*model_, qd); !s) {
    return Error{"joint velocity jog rejected: " + s.error().message};
  }
  for (int j = 0; j < model_->dof(); ++j) {
    if (std::abs(qd[j]) > model_->max_velocities()[j]) {
      return Error{"joint velocity jog rejected: " + core::joint_label(*model_, j) + " at " +
                   core::format_joint_value(*model_, j, qd[j]) + "/s exceeds its max velocity of " +
                   core::format_joint_value(*model_, j, model_->max_velocities()[j]) + "/s"};
    }
  }
  jog_kind_ = JogKind::kVelocity;
  jog_velocity_ = qd;
  jog_expires_at_ = expires_at;
  stop_reason_.clear();
  mode_ = core::RobotMode::kJogging;
  return Status::Ok();
}

Result<core::MotionOutcome> SimulatedRobot::jog(const core::MotionCommand& command,
                                                double expires_at,
                                                const core::MotionOptions& motion_options) {
  std::lock_guard lock(mutex_);
  catch_up();
  if (Status s = check_can_move("jog"); !s) return s.error();
  if (Status s = check_jog_expiry(expires_at); !s) return s.error();
  const bool accumulating = mode_ == core::RobotMode::kJogging && jog_kind_ == JogKind::kTarget;
  const Eigen::VectorXd base = accumulating ? jog_target_ : q_cmd_;
  core::MotionOutcome outcome = core::apply_motion(*model_, base, command, motion_options);
  if (!outcome.accepted) return Error{"jog rejected: " + outcome.rejection.message};
  jog_kind_ = JogKind::kTarget;
  jog_target_ = outcome.q;
  jog_expires_at_ = expires_at;
  stop_reason_.clear();
  mode_ = core::RobotMode::kJogging;
  return outcome;
}

Result<TrajectoryAcceptance> SimulatedRobot::execute(const std::string& id,
                                                     const core::Trajectory& trajectory) {
  // Validation needs only the immutable model: done before taking the lock, so that a long
  // trajectory does not hold up the servo.
  return start_trajectory(id, TrajectoryReference::FromTrajectory(*model_, trajectory));
}

Result<TrajectoryAcceptance> SimulatedRobot::execute(const std::string& id,
                                                     core::TimedWaypoints waypoints) {
  return start_trajectory(id,
                          TrajectoryReference::FromTimedWaypoints(*model_, std::move(waypoints)));
}

Result<TrajectoryAcceptance> SimulatedRobot::start_trajectory(
    const std::string& id, Result<TrajectoryReference> reference) {
  if (id.empty()) return Error{"trajectory rejected: its id is empty"};
  if (id.size() > options_.max_trajectory_id_length) {
    return Error{"trajectory rejected: its id is " + std::to_string(id.size()) +
                 " characters long, more than the maximum of " +
                 std::to_string(options_.max_trajectory_id_length)};
  }
  if (!is_printable_ascii(id)) {
    return Error{"trajectory rejected: its id contains characters other than printable ASCII"};
  }
  const std::string label = "trajectory '" + id + "'";
  std::lock_guard lock(mutex_);
  catch_up();
  if (const auto it = records_.find(id); it != records_.end()) {
    return TrajectoryAcceptance{true, it->second};
  }
  if (Status s = check_can_move(label.c_str()); !s) return s.error();
  if (mode_ != core::RobotMode::kIdle) {
    return Error{label + " rejected: the arm is " + mode_activity(mode_) +
                 "; wait until it is at rest (or cancel the motion)"};
  }
  if (!reference) return Error{label + " rejected: " + reference.error().message};
  const Eigen::VectorXd& start = reference->start();
  Eigen::Index worst = 0;
  const double deviation = (start - q_).cwiseAbs().maxCoeff(&worst);
  if (deviation > options_.start_tolerance) {
    const int j = static_cast<int>(worst);
    return Error{label + " rejected: it starts " + core::format_joint_value(*model_, j, deviation) +
                 " away from the arm: " + core::joint_label(*model_, j) + " is at " +
                 core::format_joint_value(*model_, j, q_[j]) + ", the trajectory starts at " +
                 core::format_joint_value(*model_, j, start[j]) + " (tolerance " +
                 core::format_joint_value(*model_, j, options_.start_tolerance) + ")"};
  }
  core::TrajectoryRecord record;
  record.id = id;
  record.accepted_at = now();
  record.duration = reference->duration();
  records_.emplace(id, record);
  const bool at_start = q_cmd_ == start;
  trajectory_.emplace(ActiveTrajectory{std::move(reference).value(), id, !at_start, now(), 0});
  mode_ = core::RobotMode::kTrajectory;
  stop_reason_.clear();
  if (at_start) apply_gripper_events(0.0);
  return TrajectoryAcceptance{false, record};
}

void SimulatedRobot::cancel(const std::string& reason) {
  std::lock_guard lock(mutex_);
  catch_up();
  if (mode_ == core::RobotMode::kEStopped) return;
  gripper_target_ = gripper_;
  begin_stop(reason, core::TrajectoryStatus::kCancelled);
}

Status SimulatedRobot::set_gripper(double opening) {
  std::lock_guard lock(mutex_);
  catch_up();
  if (mode_ == core::RobotMode::kEStopped) {
    return Error{"gripper command rejected: the e-stop is engaged (since t = " +
                 core::format_seconds(estop_time_) + ": " + estop_reason_ +
                 "); reset it once the arm is at rest"};
  }
  if (!(std::isfinite(opening) && opening >= 0.0 && opening <= 1.0)) {
    return Error{"gripper command rejected: opening " + core::format_number(opening) +
                 " is outside [0, 1] (0 closed, 1 open)"};
  }
  gripper_target_ = opening;
  return Status::Ok();
}

void SimulatedRobot::estop(const std::string& reason) {
  std::lock_guard lock(mutex_);
  catch_up();
  if (mode_ == core::RobotMode::kEStopped) return;
  if (trajectory_) finish_trajectory(core::TrajectoryStatus::kAborted, "e-stop: " + reason);
  mode_ = core::RobotMode::kEStopped;
  estop_reason_ = reason;
  estop_time_ = now();
  qd_cmd_.setZero();
  qd_.setZero();
  jog_expires_at_ = 0.0;
  stop_reason_.clear();
  gripper_target_ = gripper_;
}

Status SimulatedRobot::reset_estop() {
  std::lock_guard lock(mutex_);
  catch_up();
  if (mode_ != core::RobotMode::kEStopped) return Status::Ok();
  for (int j = 0; j < model_->dof(); ++j) {
    const auto& fault = faults_[static_cast<size_t>(j)];
    const bool drifting =
        fault && fault->kind == JointFaultKind::kDrift && fault->drift_rate != 0.0;
    if (qd_[j] != 0.0 || drifting) {
      const double speed = qd_[j] != 0.0 ? qd_[j] : fault->drift_rate;
      return Error{"cannot reset the e-stop while the arm moves: " + core::joint_label(*model_, j) +
                   " moves at " + core::format_joint_value(*model_, j, speed) +
                   "/s; wait until it is at rest"};
    }
  }
  sync_command_to_measured();
  mode_ = core::RobotMode::kIdle;
  estop_reason_.clear();
  return Status::Ok();
}

void SimulatedRobot::clear_fault() {
  std::lock_guard lock(mutex_);
  fault_.reset();
}

Status SimulatedRobot::inject_fault(const JointFault& fault) {
  std::lock_guard lock(mutex_);
  catch_up();
  if (fault.joint < 0 || fault.joint >= model_->dof()) {
    return Error{"fault injection: joint index " + std::to_string(fault.joint) +
                 " is out of range (0 to " + std::to_string(model_->dof() - 1) + ")"};
  }
  if (fault.kind == JointFaultKind::kLag &&
      !(std::isfinite(fault.lag_time_constant) && fault.lag_time_constant > 0.0)) {
    return Error{
        "fault injection: lag time constant must be a positive finite number of "
        "seconds, got " +
        core::format_number(fault.lag_time_constant)};
  }
  if (fault.kind == JointFaultKind::kDrift && !std::isfinite(fault.drift_rate)) {
    return Error{"fault injection: drift rate is not a finite number"};
  }
  // Continue from where the joint measures now, so that injecting never makes it jump.
  drift_offset_[fault.joint] = q_[fault.joint] - q_cmd_[fault.joint];
  faults_[static_cast<size_t>(fault.joint)] = fault;
  return Status::Ok();
}

Status SimulatedRobot::clear_injected_faults() {
  std::lock_guard lock(mutex_);
  catch_up();
  if (mode_ != core::RobotMode::kIdle && mode_ != core::RobotMode::kEStopped) {
    return Error{std::string("clear injected faults while the arm is idle or e-stopped; it is ") +
                 mode_activity(mode_)};
  }
  std::fill(faults_.begin(), faults_.end(), std::nullopt);
  sync_command_to_measured();
  return Status::Ok();
}

}  // namespace telear::sim
