#include "telear/drivers/ros1_robot_driver.hpp"

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <map>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>
#include <vector>

#include <spdlog/spdlog.h>

#include "drivers/driver_support.hpp"
#include "drivers/ros1/ros1_link.hpp"
#include "telear/core/clock.hpp"
#include "telear/core/motion_command.hpp"
#include "telear/core/number_format.hpp"
#include "telear/core/trajectory.hpp"
#include "telear/core/workspace.hpp"

namespace telear::drivers {
namespace {

const char* goal_end_text(ros1::GoalEnd end) {
  switch (end) {
    case ros1::GoalEnd::kSucceeded:
      return "succeeded";
    case ros1::GoalEnd::kAborted:
      return "aborted";
    case ros1::GoalEnd::kPreempted:
      return "preempted";
    case ros1::GoalEnd::kRejected:
      return "rejected";
    case ros1::GoalEnd::kLost:
      break;
  }
  return "lost";
}

}  // namespace

class Ros1RobotDriver final : public core::RobotDriver {
 public:
  Ros1RobotDriver(const core::RobotDescription& description, Ros1DriverOptions options)
      : model_(description.model),
        urdf_(core::urdf_text_for_clients(description)),
        tip_link_(description.tip_link),
        root_link_(description.root_link.empty() ? "base_link" : description.root_link),
        options_(std::move(options)),
        epoch_ns_(core::monotonic_ns()) {
    const int dof = model_->dof();
    joint_names_ = joint_names(*model_);
    if (description.gripper) gripper_max_opening_m_ = description.gripper->max_opening_m;
    q_ = Eigen::VectorXd::Zero(dof);
    qd_ = Eigen::VectorXd::Zero(dof);
  }

  Status start() {
    ros1::LinkOptions link;
    link.master_uri = options_.master_uri;
    link.joint_states_topic = options_.joint_states_topic;
    link.controller_ns = options_.controller_ns;
    link.gripper_ns = options_.gripper_ns;
    link.ghost_topic = options_.ghost_topic;
    link.workspace_topic = options_.workspace_topic;
    link.robot_description = urdf_;
    std::string error;
    ros1::LinkHandlers handlers;
    handlers.on_state = [this](const ros1::JointStateMessage& message) { on_joint_state(message); };
    handlers.on_goal_done = [this](std::uint64_t goal, const ros1::GoalOutcome& outcome) {
      on_goal_done(goal, outcome);
    };
    handlers.on_goal_feedback = [this](std::uint64_t goal, const ros1::GoalFeedback& feedback) {
      on_goal_feedback(goal, feedback);
    };
    handlers.log = [](const std::string& line) { spdlog::info("ros1: {}", line); };
    link_ = ros1::Link::start(link, std::move(handlers), &error);
    if (!link_) return Error{"ROS 1 driver: " + error};
    timer_ = std::thread([this] { run_timer(); });
    return Status::Ok();
  }

  ~Ros1RobotDriver() override {
    {
      std::lock_guard lock(mutex_);
      stopping_ = true;
    }
    timer_wake_.notify_all();
    if (timer_.joinable()) timer_.join();
    link_.reset();  // cancels a running goal
  }

  const core::RobotModelPtr& model() const override { return model_; }
  std::string name() const override { return "ros1"; }
  std::string urdf() const override { return urdf_; }
  std::string tip_link() const override { return tip_link_; }
  double start_tolerance() const override { return options_.start_tolerance; }

  core::DriverSnapshot snapshot() const override {
    const std::int64_t now = core::monotonic_ns();
    std::lock_guard lock(mutex_);
    core::DriverSnapshot snapshot;
    core::RobotState& state = snapshot.state;
    snapshot.capture_ns = have_state_ ? capture_ns_ : now;
    state.time = robot_s(snapshot.capture_ns);
    state.q = q_;
    state.qd = qd_;
    state.q_commanded = q_;
    state.qd_commanded = qd_;
    state.gripper = gripper_opening_;
    state.gripper_target = gripper_opening_;
    state.estop = estop_;
    state.estop_reason = estop_reason_;
    state.estop_time = estop_time_;
    state.mode = mode_locked();
    if (active_) {
      const core::TrajectoryRecord& record = records_.at(active_->id);
      state.trajectory_id = active_->id;
      state.trajectory_duration = record.duration;
      const double elapsed_s =
          active_->feedback_time_s.value_or(core::ns_to_s(now - active_->accepted_ns));
      state.trajectory_time = std::clamp(elapsed_s, 0.0, record.duration);
      if (active_->desired) state.q_commanded = *active_->desired;
      state.trajectory_progress =
          record.duration > 0.0 ? state.trajectory_time / record.duration : 1.0;
    }
    if (jog_) state.jog_expires_at = robot_s(jog_->expires_ns);
    state.stop_reason = stop_reason_;
    if (auto fault = fault_locked(now)) state.fault = std::move(fault);
    return snapshot;
  }

  std::optional<core::TrajectoryRecord> trajectory_record(const std::string& id) const override {
    std::lock_guard lock(mutex_);
    const auto found = records_.find(id);
    if (found == records_.end()) return std::nullopt;
    return found->second;
  }

  Result<core::MotionOutcome> jog(const core::MotionCommand& command,
                                  std::int64_t expires_ns) override {
    std::lock_guard lock(mutex_);
    const std::int64_t now = core::monotonic_ns();
    if (Status s = check_can_move_locked("jog", now); !s) return s.error();
    if (Status s = check_jog_expiry(expires_ns, now, options_.max_jog_duration_s); !s) {
      return s.error();
    }
    // A jog while a jog's goal runs adds to that jog's target, as on the simulated arm.
    const Eigen::VectorXd base = jog_ ? jog_->target : q_;
    core::MotionOutcome outcome = core::apply_motion(*model_, base, command);
    if (!outcome.accepted) return Error{"jog rejected: " + outcome.rejection.message};
    if (Status s = send_jog_locked(outcome.q, std::nullopt, expires_ns); !s) return s.error();
    return outcome;
  }

  Status jog_velocity(const Eigen::VectorXd& qd, std::int64_t expires_ns) override {
    std::lock_guard lock(mutex_);
    const std::int64_t now = core::monotonic_ns();
    if (qd.size() != model_->dof() || !qd.allFinite()) {
      return Error{"jog rejected: the velocity must be " + std::to_string(model_->dof()) +
                   " finite values"};
    }
    if (Status s = check_can_move_locked("jog", now); !s) return s;
    if (Status s = check_jog_expiry(expires_ns, now, options_.max_jog_duration_s); !s) return s;
    if (qd.isZero()) {
      stop_locked("jog at zero velocity");
      return Status::Ok();
    }
    // Held until the expiry: the goal ends where the velocity would take the arm by then,
    // short of a joint limit.
    const double horizon_s = core::ns_to_s(expires_ns - now);
    const Eigen::VectorXd target =
        (q_ + qd * horizon_s).cwiseMax(model_->lower_limits()).cwiseMin(model_->upper_limits());
    return send_jog_locked(target, horizon_s, expires_ns);
  }

  Result<core::DriverAcceptance> execute(const std::string& id,
                                         const core::TimedWaypoints& waypoints) override {
    std::lock_guard lock(mutex_);
    const std::int64_t now = core::monotonic_ns();
    if (const auto first = records_.find(id); first != records_.end()) {
      return core::DriverAcceptance{true, first->second, accepted_ns_.at(id)};
    }
    const std::string what = "trajectory " + quoted(id);
    if (Status s = check_can_move_locked(what.c_str(), now); !s) return s.error();
    if (jog_) {
      return Error{what + " rejected: the arm is jogging; wait until it is at rest (or cancel)"};
    }
    if (waypoints.q.empty() || waypoints.q.size() != waypoints.times.size()) {
      return Error{what + " rejected: no samples"};
    }
    // Without a gripper action the opening stays what the state reports (no-op events only).
    const bool has_gripper = !options_.gripper_ns.empty();
    if (!has_gripper) {
      if (Status s = check_gripper_events_keep(
              what, waypoints.gripper, gripper_opening_,
              "this robot server has no gripper action (telear robot-server --gripper-action NS)");
          !s) {
        return s.error();
      }
    }
    GoalPoints points = goal_points(waypoints);
    ros1::TrajectoryGoal goal{joint_names_, std::move(points.times_ns),
                              std::move(points.positions)};
    const double t0 = waypoints.times.front();
    const std::uint64_t number = link_->send_trajectory(goal);
    if (number == 0) {
      return Error{what + " rejected: the action server " + options_.controller_ns +
                   " is not connected"};
    }
    core::TrajectoryRecord record;
    record.id = id;
    record.status = core::TrajectoryStatus::kRunning;
    record.accepted_at = robot_s(now);
    record.duration = waypoints.times.back() - t0;
    records_[id] = record;
    accepted_ns_[id] = now;
    active_ = Active{id, number, now, std::nullopt, std::nullopt};
    stop_reason_.clear();
    for (const core::GripperEvent& event : waypoints.gripper) {
      if (has_gripper)
        gripper_events_.push_back({now + core::s_to_ns(event.time - t0), event.opening});
    }
    timer_wake_.notify_all();
    return core::DriverAcceptance{false, record, now};
  }

  void stop(const std::string& reason) override {
    std::lock_guard lock(mutex_);
    stop_locked(reason);
  }

  Status set_gripper(double opening) override {
    std::lock_guard lock(mutex_);
    if (Status s = check_can_move_locked("gripper command", core::monotonic_ns()); !s) return s;
    return send_gripper_locked(opening);
  }

  void estop(const std::string& reason) override {
    std::lock_guard lock(mutex_);
    if (!estop_) {
      estop_ = true;
      estop_reason_ = reason;
      estop_time_ = robot_s(core::monotonic_ns());
    }
    stop_locked("e-stop: " + estop_reason_);
  }

  Status reset_estop() override {
    std::lock_guard lock(mutex_);
    if (!estop_) return Status::Ok();
    if (active_) {
      return Error{
          "cannot reset the e-stop while the controller has not confirmed the stop of "
          "trajectory " +
          quoted(active_->id) + "; wait until it is at rest"};
    }
    estop_ = false;
    estop_reason_.clear();
    return Status::Ok();
  }

  void show_preview(const std::string& plan_id, const core::TimedWaypoints& samples) override {
    if (samples.q.empty()) return;
    std::lock_guard lock(mutex_);
    spdlog::debug("ros1: playing preview '{}' on {}", plan_id, options_.ghost_topic);
    preview_.start(samples, core::monotonic_ns());
    timer_wake_.notify_all();
  }

  void show_ghost(const Eigen::VectorXd& q, double /*gripper*/) override {
    std::lock_guard lock(mutex_);
    // A preview being played shows the plan; the rehearsed pose takes over after it.
    if (preview_.playing()) return;
    link_->publish_ghost(joint_names_, std::vector<double>(q.data(), q.data() + q.size()));
  }

  void show_workspace(const core::Workspace& workspace) override {
    std::vector<ros1::WorkspaceMarker> markers;
    for (const core::WorkspaceObject& object : workspace.objects) {
      ros1::WorkspaceMarker marker;
      marker.name = object.name;
      switch (object.shape) {
        case core::ShapeKind::kBox:
          marker.shape = ros1::WorkspaceMarker::Shape::kBox;
          marker.scale = {object.size_m.x(), object.size_m.y(), object.size_m.z()};
          break;
        case core::ShapeKind::kCylinder:
          marker.shape = ros1::WorkspaceMarker::Shape::kCylinder;
          marker.scale = {2 * object.radius_m, 2 * object.radius_m, object.length_m};
          break;
        case core::ShapeKind::kSphere:
          marker.shape = ros1::WorkspaceMarker::Shape::kSphere;
          marker.scale = {2 * object.radius_m, 2 * object.radius_m, 2 * object.radius_m};
          break;
        case core::ShapeKind::kMesh:
          marker.shape = ros1::WorkspaceMarker::Shape::kMesh;
          marker.scale = {object.mesh_scale.x(), object.mesh_scale.y(), object.mesh_scale.z()};
          marker.mesh_resource = "file://" + object.mesh_path;
          break;
      }
      const Eigen::Vector3d p = object.T_base_object.translation();
      const Eigen::Quaterniond r(object.T_base_object.linear());
      marker.position = {p.x(), p.y(), p.z()};
      marker.orientation = {r.x(), r.y(), r.z(), r.w()};
      marker.colour = {object.colour.x(), object.colour.y(), object.colour.z()};
      markers.push_back(std::move(marker));
    }
    link_->publish_workspace(root_link_, markers);
  }

 private:
  struct Active {
    std::string id;
    std::uint64_t goal = 0;
    std::int64_t accepted_ns = 0;
    // From the action's feedback: the controller's setpoint (model order) and its time into
    // the goal; until the first, the samples' time since acceptance and the measured q.
    std::optional<Eigen::VectorXd> desired;
    std::optional<double> feedback_time_s;
  };
  struct Jog {
    std::uint64_t goal = 0;
    Eigen::VectorXd target;
    std::int64_t expires_ns = 0;
  };
  struct TimedGripperEvent {
    std::int64_t at_ns = 0;
    double opening = 0.0;
  };

  double robot_s(std::int64_t ns) const { return core::ns_to_s(ns - epoch_ns_); }

  core::RobotMode mode_locked() const {
    if (estop_) return core::RobotMode::kEStopped;
    if (!stop_reason_.empty() && (active_ || jog_)) return core::RobotMode::kStopping;
    if (active_) return core::RobotMode::kTrajectory;
    if (jog_) return core::RobotMode::kJogging;
    return core::RobotMode::kIdle;
  }

  // Why the arm cannot be commanded now, or nothing.
  std::optional<std::string> fault_locked(std::int64_t now) const {
    const ros1::LinkHealth health = link_->health();
    if (!health.master) return "the ROS master does not answer (" + master_text() + ")";
    if (!have_state_) {
      return "no sensor_msgs/JointState on " + options_.joint_states_topic + " yet";
    }
    if (!missing_joint_.empty()) {
      return options_.joint_states_topic + " has no joint " + quoted(missing_joint_) +
             " (the robot's joints: " + joint_list(joint_names_) + ")";
    }
    const double silent_s = core::ns_to_s(now - last_receipt_ns_);
    if (silent_s > options_.silence_timeout_s) {
      return "the arm is silent: no " + options_.joint_states_topic + " for " +
             core::format_number(silent_s, "%.2f s") + " (limit " +
             core::format_number(options_.silence_timeout_s, "%.2f s") + ")";
    }
    if (!health.controller) {
      return "the action server " + options_.controller_ns +
             " (control_msgs/FollowJointTrajectory) is not connected";
    }
    return std::nullopt;
  }

  std::string master_text() const {
    return options_.master_uri.empty() ? std::string("$ROS_MASTER_URI") : options_.master_uri;
  }

  Status check_can_move_locked(const std::string& what, std::int64_t now) const {
    return check_can_move(what, estop_, estop_reason_,
                          active_ ? std::optional<std::string>(active_->id) : std::nullopt,
                          fault_locked(now));
  }

  // A goal from the measured position to `target`: over `duration_s` (a velocity jog), or
  // timed by core's parameterization at the joints' limits.
  Status send_jog_locked(const Eigen::VectorXd& target, std::optional<double> duration_s,
                         std::int64_t expires_ns) {
    auto points = jog_points(*model_, q_, target, duration_s, options_.jog_sample_rate_hz);
    if (!points) return points.error();
    ros1::TrajectoryGoal goal{joint_names_, std::move(points->times_ns),
                              std::move(points->positions)};
    const std::uint64_t number = link_->send_trajectory(goal);
    if (number == 0) {
      return Error{"jog rejected: the action server " + options_.controller_ns +
                   " is not connected"};
    }
    jog_ = Jog{number, target, expires_ns};
    stop_reason_.clear();
    timer_wake_.notify_all();
    return Status::Ok();
  }

  Status send_gripper_locked(double opening) {
    if (options_.gripper_ns.empty()) {
      return Error{
          "gripper command rejected: this robot server has no gripper action "
          "(telear robot-server --gripper-action NS)"};
    }
    const double gap_m = std::clamp(opening, 0.0, 1.0) * gripper_max_opening_m_;
    if (!link_->send_gripper(gap_m, options_.gripper_max_effort_n)) {
      return Error{"gripper command rejected: the gripper action server " + options_.gripper_ns +
                   " is not connected"};
    }
    gripper_opening_ = std::clamp(opening, 0.0, 1.0);
    return Status::Ok();
  }

  void stop_locked(const std::string& reason) {
    gripper_events_.clear();
    if (!active_ && !jog_) return;
    stop_reason_ = reason;
    link_->cancel_trajectory();
  }

  void on_joint_state(const ros1::JointStateMessage& message) {
    const std::int64_t now = core::monotonic_ns();
    std::lock_guard lock(mutex_);
    last_receipt_ns_ = now;
    have_state_ = true;
    // Map by name; a message that lacks one of the model's joints changes nothing but the
    // fault (a partial vector would put a stale value beside fresh ones).
    const auto q = values_by_name(joint_names_, message.name, message.position, &missing_joint_);
    if (!q) return;
    // Velocities are optional in a JointState (zero where absent).
    const Eigen::VectorXd qd =
        values_by_name(joint_names_, message.name, message.velocity)
            .value_or(Eigen::VectorXd::Zero(static_cast<Eigen::Index>(joint_names_.size())));
    missing_joint_.clear();
    q_ = *q;
    qd_ = qd;
    capture_ns_ = std::min(message.capture_ns, now);
  }

  void on_goal_feedback(std::uint64_t goal, const ros1::GoalFeedback& feedback) {
    std::lock_guard lock(mutex_);
    if (!active_ || active_->goal != goal) return;
    auto desired = values_by_name(joint_names_, feedback.joint_names, feedback.desired);
    if (!desired) return;
    active_->desired = std::move(desired);
    active_->feedback_time_s = feedback.time_from_start_s;
  }

  void on_goal_done(std::uint64_t goal, const ros1::GoalOutcome& outcome) {
    std::lock_guard lock(mutex_);
    const std::int64_t now = core::monotonic_ns();
    if (jog_ && jog_->goal == goal) {
      jog_.reset();
      if (!active_) stop_reason_.clear();
      return;
    }
    if (!active_ || active_->goal != goal) return;  // replaced by a newer goal
    core::TrajectoryRecord& record = records_.at(active_->id);
    record.finished_at = robot_s(now);
    switch (outcome.end) {
      case ros1::GoalEnd::kSucceeded:
        record.status = core::TrajectoryStatus::kCompleted;
        break;
      case ros1::GoalEnd::kPreempted:
        record.status =
            estop_ ? core::TrajectoryStatus::kAborted : core::TrajectoryStatus::kCancelled;
        record.message = stop_reason_.empty() ? "preempted by the controller" : stop_reason_;
        break;
      default:
        record.status = core::TrajectoryStatus::kAborted;
        record.message =
            std::string("the controller ") + goal_end_text(outcome.end) + " the goal" +
            (outcome.error_string.empty() ? std::string() : ": " + outcome.error_string) +
            " (error_code " + std::to_string(outcome.error_code) + ")";
        break;
    }
    spdlog::info("ros1: trajectory '{}' {} ({})", record.id, core::to_string(record.status),
                 outcome.state);
    active_.reset();
    gripper_events_.clear();
    if (!jog_) stop_reason_.clear();
  }

  // Jog expiries, a plan's gripper events and the ghost's frames, on the server clock.
  void run_timer() {
    std::unique_lock lock(mutex_);
    while (!stopping_) {
      const std::int64_t now = core::monotonic_ns();
      if (jog_ && stop_reason_.empty() && now >= jog_->expires_ns) {
        stop_locked("jog expired");
      }
      while (!gripper_events_.empty() && gripper_events_.front().at_ns <= now) {
        const double opening = gripper_events_.front().opening;
        gripper_events_.erase(gripper_events_.begin());
        if (Status s = send_gripper_locked(opening); !s)
          spdlog::warn("ros1: {}", s.error().message);
      }
      std::int64_t next = now + 100'000'000;
      if (preview_.playing()) {
        const PreviewPlayback::Frame frame = preview_.advance(now, options_.ghost_rate_hz);
        link_->publish_ghost(joint_names_,
                             std::vector<double>(frame.q.data(), frame.q.data() + frame.q.size()));
        if (frame.next_ns) next = std::min(next, *frame.next_ns);
      }
      if (jog_ && stop_reason_.empty()) next = std::min(next, jog_->expires_ns);
      if (!gripper_events_.empty()) next = std::min(next, gripper_events_.front().at_ns);
      timer_wake_.wait_for(lock, std::chrono::nanoseconds(std::max<std::int64_t>(next - now, 0)));
    }
  }

  core::RobotModelPtr model_;
  std::string urdf_, tip_link_, root_link_;
  Ros1DriverOptions options_;
  std::int64_t epoch_ns_;
  std::vector<std::string> joint_names_;
  double gripper_max_opening_m_ = 0.08;

  mutable std::mutex mutex_;
  std::condition_variable timer_wake_;
  bool stopping_ = false;
  bool have_state_ = false;
  std::int64_t last_receipt_ns_ = 0, capture_ns_ = 0;
  std::string missing_joint_;
  Eigen::VectorXd q_, qd_;
  double gripper_opening_ = 0.0;
  bool estop_ = false;
  std::string estop_reason_;
  double estop_time_ = 0.0;
  std::string stop_reason_;  // a stop was asked for and the controller has not confirmed it
  std::optional<Active> active_;
  std::optional<Jog> jog_;
  std::vector<TimedGripperEvent> gripper_events_;  // in time order
  PreviewPlayback preview_;                        // played on the ghost topic
  std::map<std::string, core::TrajectoryRecord> records_;
  std::map<std::string, std::int64_t> accepted_ns_;

  std::unique_ptr<ros1::Link> link_;  // last: its threads call back into the members above
  std::thread timer_;
};

bool ros1_driver_built() {
  return true;
}

Result<std::unique_ptr<core::RobotDriver>> make_ros1_robot_driver(
    const core::RobotDescription& description, const Ros1DriverOptions& options) {
  if (!(options.silence_timeout_s > 0.0) || !(options.start_tolerance > 0.0) ||
      !(options.jog_sample_rate_hz > 0.0)) {
    return Error{
        "ROS 1 driver: the silence timeout, start tolerance and jog sample rate must be "
        "positive"};
  }
  for (const core::Joint& joint : description.model->joints()) {
    if (joint.name.empty()) {
      return Error{"ROS 1 driver: the robot's joints need names to match " +
                   options.joint_states_topic + " (give the robot's URDF)"};
    }
  }
  auto driver = std::make_unique<Ros1RobotDriver>(description, options);
  if (Status s = driver->start(); !s) return s.error();
  return std::unique_ptr<core::RobotDriver>(std::move(driver));
}

}  // namespace telear::drivers
