#include "telear/drivers/ros2_robot_driver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdlib>
#include <map>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>
#include <vector>

#include <spdlog/spdlog.h>

#include "drivers/driver_support.hpp"
#include "drivers/ros2/dds_link.hpp"
#include "drivers/ros2/ros2_names.hpp"
#include "telear/core/clock.hpp"
#include "telear/core/motion_command.hpp"
#include "telear/core/number_format.hpp"
#include "telear/core/trajectory.hpp"

namespace telear::drivers {
namespace {

// The gripper opening the state reports: this driver has no gripper.
constexpr double kGripperOpening = 0.0;

std::int64_t realtime_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

// The ROS and DDS names the driver works with, checked once.
struct Ros2Names {
  std::uint32_t domain_id = 0;
  std::string trajectory_topic;  // ROS name: <controller>/joint_trajectory
  ros2::LinkOptions link;
};

Result<Ros2Names> resolve_names(const Ros2DriverOptions& options) {
  Ros2Names names;
  auto domain = ros2::resolve_domain_id(options.domain_id, std::getenv("ROS_DOMAIN_ID"));
  if (!domain) return domain.error();
  names.domain_id = *domain;
  names.link.domain_id = *domain;
  auto states = ros2::dds_topic_name(options.joint_states_topic,
                                     "the joint states topic (--ros2-joint-states)");
  if (!states) return states.error();
  names.link.joint_states_topic = *states;
  if (!ros2::is_absolute_ros_name(options.controller)) {
    return Error{
        "the controller (--ros2-controller) must be an absolute ROS 2 name such as "
        "/joint_trajectory_controller, got '" +
        options.controller + "'"};
  }
  names.trajectory_topic = options.controller + "/joint_trajectory";
  names.link.trajectory_topic = "rt" + names.trajectory_topic;
  auto ghost = ros2::dds_topic_name(options.ghost_topic, "the ghost topic");
  if (!ghost) return ghost.error();
  names.link.ghost_topic = *ghost;
  return names;
}

}  // namespace

class Ros2RobotDriver final : public core::RobotDriver {
 public:
  Ros2RobotDriver(const core::RobotDescription& description, Ros2DriverOptions options,
                  Ros2Names names)
      : model_(description.model),
        urdf_(core::urdf_text_for_clients(description)),
        tip_link_(description.tip_link),
        options_(std::move(options)),
        names_(std::move(names)),
        epoch_ns_(core::monotonic_ns()) {
    const int dof = model_->dof();
    joint_names_ = joint_names(*model_);
    q_ = Eigen::VectorXd::Zero(dof);
    qd_ = Eigen::VectorXd::Zero(dof);
  }

  Status start() {
    std::string error;
    link_ = ros2::Link::start(
        names_.link, [this](const ros2::JointStateMessage& message) { on_joint_state(message); },
        [](const std::string& line) { spdlog::info("ros2: {}", line); }, &error);
    if (!link_) return Error{"ROS 2 driver: " + error};
    timer_ = std::thread([this] { run_timer(); });
    return Status::Ok();
  }

  ~Ros2RobotDriver() override {
    {
      std::lock_guard lock(mutex_);
      stopping_ = true;
      // The server is going away: an arm still moving is told to hold (the writer lingers
      // until the controller has it).
      stop_locked("the robot server shut down");
    }
    timer_wake_.notify_all();
    if (timer_.joinable()) timer_.join();
    link_.reset();
  }

  const core::RobotModelPtr& model() const override { return model_; }
  std::string name() const override { return "ros2"; }
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
    state.gripper = kGripperOpening;
    state.gripper_target = kGripperOpening;
    state.estop = estop_;
    state.estop_reason = estop_reason_;
    state.estop_time = estop_time_;
    state.mode = mode_locked();
    if (active_) {
      const core::TrajectoryRecord& record = records_.at(active_->id);
      state.trajectory_id = active_->id;
      state.trajectory_duration = record.duration;
      state.trajectory_time =
          std::clamp(core::ns_to_s(now - active_->accepted_ns), 0.0, record.duration);
      state.trajectory_progress =
          record.duration > 0.0 ? state.trajectory_time / record.duration : 1.0;
    }
    if (jog_) state.jog_expires_at = robot_s(jog_->expires_ns);
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
    // A jog while a jog's trajectory runs adds to that jog's target, as on the simulated arm.
    const Eigen::VectorXd base = jog_ ? Eigen::VectorXd(jog_->last()) : q_;
    core::MotionOutcome outcome = core::apply_motion(*model_, base, command);
    if (!outcome.accepted) return Error{"jog rejected: " + outcome.rejection.message};
    if (Status s = send_jog_locked(outcome.q, std::nullopt, expires_ns, now); !s) {
      return s.error();
    }
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
    // Held until the expiry: the trajectory ends where the velocity would take the arm by
    // then, short of a joint limit.
    const double horizon_s = core::ns_to_s(expires_ns - now);
    const Eigen::VectorXd target =
        (q_ + qd * horizon_s).cwiseMax(model_->lower_limits()).cwiseMin(model_->upper_limits());
    return send_jog_locked(target, horizon_s, expires_ns, now);
  }

  Result<core::DriverAcceptance> execute(const std::string& id,
                                         const core::TimedWaypoints& waypoints) override {
    std::lock_guard lock(mutex_);
    const std::int64_t now = core::monotonic_ns();
    if (const auto first = records_.find(id); first != records_.end()) {
      return core::DriverAcceptance{true, first->second, accepted_ns_.at(id)};
    }
    const std::string what = "trajectory " + quoted(id);
    if (Status s = check_can_move_locked(what, now); !s) return s.error();
    if (jog_) {
      return Error{what + " rejected: the arm is jogging; wait until it is at rest (or cancel)"};
    }
    if (waypoints.q.empty() || waypoints.q.size() != waypoints.times.size()) {
      return Error{what + " rejected: no samples"};
    }
    // No gripper: the opening stays what the state reports (0). Events that keep it (a plan's
    // waypoints carry the opening even when it does not change) are no-ops, as in the ROS 1
    // driver without a gripper action; one that changes it is refused rather than run without
    // the grasp it was planned for.
    if (Status s = check_gripper_events_keep(what, waypoints.gripper, kGripperOpening,
                                             "the ROS 2 driver has no gripper interface");
        !s) {
      return s.error();
    }
    GoalPoints points = goal_points(waypoints);
    ros2::TrajectoryMessage message{joint_names_, std::move(points.times_ns),
                                    std::move(points.positions)};
    const double t0 = waypoints.times.front();
    if (!link_->publish_trajectory(message)) {
      return Error{what + " rejected: it could not be written to " + names_.trajectory_topic};
    }
    core::TrajectoryRecord record;
    record.id = id;
    record.status = core::TrajectoryStatus::kRunning;
    record.accepted_at = robot_s(now);
    record.duration = waypoints.times.back() - t0;
    records_[id] = record;
    accepted_ns_[id] = now;
    active_ = Motion{id, now, now + message.times_ns.back(), 0, std::move(message)};
    timer_wake_.notify_all();
    return core::DriverAcceptance{false, record, now};
  }

  void stop(const std::string& reason) override {
    std::lock_guard lock(mutex_);
    stop_locked(reason);
  }

  Status set_gripper(double /*opening*/) override {
    return Error{
        "gripper command rejected: the ROS 2 driver has no gripper interface "
        "(ros2_control's gripper controllers take actions, docs/ros2.md)"};
  }

  void estop(const std::string& reason) override {
    std::lock_guard lock(mutex_);
    if (!estop_) {
      estop_ = true;
      estop_reason_ = reason;
      estop_time_ = robot_s(core::monotonic_ns());
    }
    // Unlike stop(), also at rest: whatever else commands the controller (rqt, a script) is
    // overridden by the hold.
    if (!active_ && !jog_) {
      publish_hold_locked(core::monotonic_ns());
      return;
    }
    stop_locked("e-stop: " + estop_reason_);
  }

  Status reset_estop() override {
    std::lock_guard lock(mutex_);
    // The hold was published when the e-stop was engaged; a topic has no acknowledgement to
    // wait for.
    estop_ = false;
    estop_reason_.clear();
    return Status::Ok();
  }

  void show_ghost(const Eigen::VectorXd& q, double /*gripper*/) override {
    std::lock_guard lock(mutex_);
    // A preview being played shows the plan; the rehearsed pose takes over after it.
    if (preview_.playing()) return;
    link_->publish_ghost(joint_names_, std::vector<double>(q.data(), q.data() + q.size()));
  }

  void show_preview(const std::string& plan_id, const core::TimedWaypoints& samples) override {
    if (samples.q.empty()) return;
    std::lock_guard lock(mutex_);
    spdlog::debug("ros2: playing preview '{}'", plan_id);
    preview_.start(samples, core::monotonic_ns());
    timer_wake_.notify_all();
  }

 private:
  // A trajectory on the controller: a plan's (id set) or a jog's.
  struct Motion {
    std::string id;
    std::int64_t accepted_ns = 0;
    std::int64_t end_ns = 0;      // accepted + its duration
    std::int64_t expires_ns = 0;  // a jog's expiry (unused for a plan)
    ros2::TrajectoryMessage sent;

    Eigen::Map<const Eigen::VectorXd> last() const {
      const std::vector<double>& q = sent.positions.back();
      return {q.data(), static_cast<Eigen::Index>(q.size())};
    }
    // Where the controller's setpoint is at `now`: its positions-only points interpolated
    // linearly in time, as the controller does.
    std::vector<double> setpoint(std::int64_t now) const {
      const std::int64_t t = now - accepted_ns;
      std::size_t k = 0;
      while (k < sent.times_ns.size() && sent.times_ns[k] <= t) ++k;
      if (k == 0) return sent.positions.front();
      if (k == sent.times_ns.size()) return sent.positions.back();
      const double s = static_cast<double>(t - sent.times_ns[k - 1]) /
                       static_cast<double>(sent.times_ns[k] - sent.times_ns[k - 1]);
      std::vector<double> q(sent.positions[k].size());
      for (std::size_t j = 0; j < q.size(); ++j) {
        q[j] = sent.positions[k - 1][j] + (sent.positions[k][j] - sent.positions[k - 1][j]) * s;
      }
      return q;
    }
  };

  double robot_s(std::int64_t ns) const { return core::ns_to_s(ns - epoch_ns_); }

  core::RobotMode mode_locked() const {
    if (estop_) return core::RobotMode::kEStopped;
    if (active_) return core::RobotMode::kTrajectory;
    if (jog_) return core::RobotMode::kJogging;
    return core::RobotMode::kIdle;
  }

  // Why the arm cannot be commanded now, or nothing.
  std::optional<std::string> fault_locked(std::int64_t now) const {
    if (!have_state_) {
      return "no sensor_msgs/msg/JointState on " + options_.joint_states_topic + " yet (DDS " +
             names_.link.joint_states_topic + ", domain " + std::to_string(names_.domain_id) + ")";
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
    if (link_->trajectory_subscribers() == 0) {
      return "nothing subscribes to " + names_.trajectory_topic +
             " (trajectory_msgs/msg/JointTrajectory): is the JointTrajectoryController active?";
    }
    return std::nullopt;
  }

  Status check_can_move_locked(const std::string& what, std::int64_t now) const {
    return check_can_move(what, estop_, estop_reason_,
                          active_ ? std::optional<std::string>(active_->id) : std::nullopt,
                          fault_locked(now));
  }

  // A trajectory from the measured position to `target`: over `duration_s` (a velocity jog),
  // or timed by core's parameterization at the joints' limits.
  Status send_jog_locked(const Eigen::VectorXd& target, std::optional<double> duration_s,
                         std::int64_t expires_ns, std::int64_t now) {
    auto points = jog_points(*model_, q_, target, duration_s, options_.jog_sample_rate_hz);
    if (!points) return points.error();
    ros2::TrajectoryMessage message{joint_names_, std::move(points->times_ns),
                                    std::move(points->positions)};
    if (!link_->publish_trajectory(message)) {
      return Error{"jog rejected: it could not be written to " + names_.trajectory_topic};
    }
    jog_ = Motion{"", now, now + message.times_ns.back(), expires_ns, std::move(message)};
    timer_wake_.notify_all();
    return Status::Ok();
  }

  // The controller's own stop: hold the arm's last measured position, at once (a one-point
  // trajectory at time_from_start 0, stamp 0, as its set_hold_position() builds). When that
  // position is stale (the arm silent or incomplete) while a trajectory runs, its setpoint now
  // stands in: holding where the arm was seconds ago would move it back, unchecked.
  void publish_hold_locked(std::int64_t now) {
    ros2::TrajectoryMessage hold;
    hold.joint_names = joint_names_;
    hold.times_ns = {0};
    const bool fresh = have_state_ && missing_joint_.empty() &&
                       core::ns_to_s(now - last_receipt_ns_) <= options_.silence_timeout_s;
    const Motion* running = active_ ? &*active_ : jog_ ? &*jog_ : nullptr;
    if (fresh) {
      hold.positions = {std::vector<double>(q_.data(), q_.data() + q_.size())};
    } else if (running != nullptr) {
      spdlog::warn(
          "ros2: the arm's position is stale; holding the running trajectory's "
          "setpoint instead");
      hold.positions = {running->setpoint(now)};
    } else {
      return;  // at rest and unheard: nothing known to hold
    }
    link_->publish_trajectory(hold);
  }

  // A controlled stop of the running trajectory or jog; the record is final at once (a topic
  // has no acknowledgement to wait for).
  void stop_locked(const std::string& reason) {
    if (!active_ && !jog_) return;
    const std::int64_t now = core::monotonic_ns();
    publish_hold_locked(now);
    jog_.reset();
    if (active_) {
      finish_locked(estop_ ? core::TrajectoryStatus::kAborted : core::TrajectoryStatus::kCancelled,
                    reason, now);
    }
  }

  void finish_locked(core::TrajectoryStatus status, const std::string& message, std::int64_t now) {
    core::TrajectoryRecord& record = records_.at(active_->id);
    record.status = status;
    record.message = message;
    record.finished_at = robot_s(now);
    spdlog::info("ros2: trajectory '{}' {}{}", record.id, core::to_string(record.status),
                 message.empty() ? "" : " (" + message + ")");
    active_.reset();
  }

  // How far the arm is from `point`: the farthest joint's index and distance.
  std::pair<int, double> farthest_joint(const Eigen::Ref<const Eigen::VectorXd>& point) const {
    Eigen::Index j = 0;
    const double distance = (q_ - point).cwiseAbs().maxCoeff(&j);
    return {static_cast<int>(j), distance};
  }

  // A trajectory or jog ends when a joint state received after its duration has the arm
  // within the start tolerance of its last point; a trajectory not there goal_time_s later
  // has failed.
  void check_motions_locked(std::int64_t now) {
    const auto reached = [&](const Motion& motion) {
      return have_state_ && missing_joint_.empty() && last_receipt_ns_ >= motion.end_ns &&
             farthest_joint(motion.last()).second <= options_.start_tolerance;
    };
    const std::int64_t grace_ns = core::s_to_ns(options_.goal_time_s);
    if (active_) {
      if (reached(*active_)) {
        finish_locked(core::TrajectoryStatus::kCompleted, "", now);
      } else if (now > active_->end_ns + grace_ns) {
        finish_locked(core::TrajectoryStatus::kAborted, not_reached_text(*active_), now);
      }
    }
    // A jog that has not arrived is stopped at its expiry (run_timer), not given up on.
    if (jog_ && reached(*jog_)) jog_.reset();
  }

  std::string not_reached_text(const Motion& motion) const {
    const std::string prefix = "the arm did not reach the trajectory's last point within " +
                               core::format_number(options_.goal_time_s, "%.2f s") +
                               " after its duration: ";
    if (last_receipt_ns_ < motion.end_ns || !missing_joint_.empty()) {
      return prefix + "no complete " + options_.joint_states_topic + " since";
    }
    const auto [j, distance] = farthest_joint(motion.last());
    return prefix + "joint " + quoted(joint_names_[static_cast<std::size_t>(j)]) + " is " +
           core::format_number(distance, "%.4f") + " from it (tolerance " +
           core::format_number(options_.start_tolerance, "%.4f") + ")";
  }

  void on_joint_state(const ros2::JointStateMessage& message) {
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
    // The stamp is ROS time on the arm's system clock; one from another clock (unsynchronised,
    // or sim time) would put the capture far off, so such an age counts as 0.
    std::int64_t age_ns = message.stamp_ns > 0 ? realtime_ns() - message.stamp_ns : 0;
    if (age_ns < 0 || age_ns > core::s_to_ns(options_.silence_timeout_s)) age_ns = 0;
    capture_ns_ = now - age_ns;
    check_motions_locked(now);
  }

  // Jog expiries, the ends of trajectories whose arm fell silent, and the ghost's frames, on
  // the server clock.
  void run_timer() {
    std::unique_lock lock(mutex_);
    const std::int64_t grace_ns = core::s_to_ns(options_.goal_time_s);
    while (!stopping_) {
      const std::int64_t now = core::monotonic_ns();
      if (jog_ && now >= jog_->expires_ns) stop_locked("jog expired");
      check_motions_locked(now);
      std::int64_t next = now + 100'000'000;
      if (preview_.playing()) {
        const PreviewPlayback::Frame frame = preview_.advance(now, options_.ghost_rate_hz);
        link_->publish_ghost(joint_names_,
                             std::vector<double>(frame.q.data(), frame.q.data() + frame.q.size()));
        if (frame.next_ns) next = std::min(next, *frame.next_ns);
      }
      if (jog_) next = std::min(next, jog_->expires_ns);
      if (active_) next = std::min(next, active_->end_ns + grace_ns + 1);
      timer_wake_.wait_for(lock, std::chrono::nanoseconds(std::max<std::int64_t>(next - now, 0)));
    }
  }

  core::RobotModelPtr model_;
  std::string urdf_, tip_link_;
  Ros2DriverOptions options_;
  Ros2Names names_;
  std::int64_t epoch_ns_;
  std::vector<std::string> joint_names_;

  mutable std::mutex mutex_;
  std::condition_variable timer_wake_;
  bool stopping_ = false;
  bool have_state_ = false;
  std::int64_t last_receipt_ns_ = 0, capture_ns_ = 0;
  std::string missing_joint_;
  Eigen::VectorXd q_, qd_;
  bool estop_ = false;
  std::string estop_reason_;
  double estop_time_ = 0.0;
  std::optional<Motion> active_;  // a plan or trajectory the controller runs
  std::optional<Motion> jog_;
  PreviewPlayback preview_;  // played on the ghost topic
  std::map<std::string, core::TrajectoryRecord> records_;
  std::map<std::string, std::int64_t> accepted_ns_;

  std::unique_ptr<ros2::Link> link_;  // last: its thread calls back into the members above
  std::thread timer_;
};

bool ros2_driver_built() {
  return true;
}

Result<std::unique_ptr<core::RobotDriver>> make_ros2_robot_driver(
    const core::RobotDescription& description, const Ros2DriverOptions& options) {
  if (!(options.silence_timeout_s > 0.0) || !(options.start_tolerance > 0.0) ||
      !(options.jog_sample_rate_hz > 0.0) || !(options.ghost_rate_hz > 0.0) ||
      !(options.goal_time_s >= 0.0)) {
    return Error{
        "ROS 2 driver: the silence timeout, start tolerance, jog sample rate and ghost "
        "rate must be positive, the goal time not negative"};
  }
  for (const core::Joint& joint : description.model->joints()) {
    if (joint.name.empty()) {
      return Error{"ROS 2 driver: the robot's joints need names to match " +
                   options.joint_states_topic + " (give the robot's URDF)"};
    }
  }
  auto names = resolve_names(options);
  if (!names) return Error{"ROS 2 driver: " + names.error().message};
  auto driver = std::make_unique<Ros2RobotDriver>(description, options, std::move(names).value());
  if (Status s = driver->start(); !s) return s.error();
  return std::unique_ptr<core::RobotDriver>(std::move(driver));
}

}  // namespace telear::drivers
