#pragma once
// The simulated robot: a joint servo that the robot server's RobotDriver wraps, and the
// "real" arm of every demo and test.
//
// Servo. Time advances in fixed servo periods dt (options.servo_period, 1 ms) on the robot's
// clock (telear/sim/sim_clock.hpp): update() integrates every whole period up to clock->now(), and
// every command first does the same, so a command takes effect at the latest period boundary
// and the robot's time is always t0 + k dt, whatever the caller's rhythm. Each period the
// active mode produces the commanded joint state (q_cmd, qd_cmd); the servo is ideal, so the
// measured state equals it unless a fault is injected (telear/sim/joint_fault.hpp).
//
//   idle        holds q_cmd, qd_cmd = 0.
//   jogging     a joint velocity (jog_velocity) or a joint target computed by core's
//               apply_motion from a motion command (jog). Each joint moves on its own within
//               its velocity and acceleration limits (telear/sim/joint_motion.hpp), landing on the
//               target at rest; the joints need not arrive together, so a jog's path is not
//               a straight line in joint space (a trajectory's is). Increments accumulate:
//               a jog received while the arm is still going to a target is applied to that
//               target, not to where the arm happens to be, so a stream of small increments
//               adds up exactly. At the jog's expiry time the arm makes a controlled stop.
//   trajectory  q_cmd(t) = reference(t - t_start) (telear/sim/trajectory_reference.hpp). When the
//               arm is within the start tolerance but not exactly at the start, it first
//               moves there like a jog, then the trajectory's clock starts.
//   stopping    a controlled stop: every joint decelerates to rest together over
//               T = max_j |qd_j| / (s a_j) (s = options.stop_deceleration_scale), each at
//               |qd_j| / T <= s a_j, so the arm stays on its path (telear/sim/joint_motion.hpp).
//   estopped    halted at once (qd = 0), latched until reset_estop().
//
// Every jog and stop also caps each joint's speed by its braking curve towards both joint
// limits, so no command can carry a joint past a limit. The hard clamp is the last line of
// defence: a measured joint beyond a limit (only a fault can get it there) is clamped to it,
// its velocity zeroed, a fault message latched and the current motion stopped.
//
// Validation. Every command is checked before it changes anything and is rejected with a
// message that says what and why: a rejected trajectory or jog never moves the arm. While the
// e-stop is engaged every motion and gripper command is rejected.
//
// Trajectory ids. Each accepted id is remembered for the robot's lifetime; executing an id
// again is answered with the first acceptance (`duplicate`) and does not move the arm, so a
// client may safely retry after a lost reply. Rejected ids are not remembered: a rejected
// trajectory never moved, so a retry is validated afresh.
//
// True model. With options.true_joint_offsets the real arm's geometry differs from the
// nominal model the robot reports in (telear/sim/true_model.hpp): true_model() is what the "real"
// scene is rendered with, at the reported q.
//
// Thread safety. Every public member function may be called from any thread: one mutex
// guards the whole state, commands and update() are serialised by it, and state() returns a
// copy taken under it. The models and options are immutable after create(). The clock must be
// thread-safe (SteadyClock and ManualClock are). Nothing blocks longer than integrating the
// periods that are due.

#include <Eigen/Core>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "telear/core/motion_command.hpp"
#include "telear/core/result.hpp"
#include "telear/core/robot_model.hpp"
#include "telear/core/robot_state.hpp"
#include "telear/core/trajectory.hpp"
#include "telear/sim/joint_fault.hpp"
#include "telear/sim/joint_motion.hpp"
#include "telear/sim/sim_clock.hpp"
#include "telear/sim/trajectory_reference.hpp"

namespace telear::sim {

struct SimulatedRobotOptions {
  Eigen::VectorXd initial_q;     // empty: zero, moved into the limits; must be within them
  double initial_gripper = 1.0;  // 0 closed .. 1 open
  double servo_period = 0.001;   // s, in (0, 0.1]
  double gripper_speed = 1.0;    // opening per second (> 0): a full stroke takes 1 s
  // How far (rad or m, per joint) the arm may be from a trajectory's start when it arrives.
  double start_tolerance = 0.01;
  // Fraction (0, 1] of each joint's max acceleration a controlled stop decelerates at.
  double stop_deceleration_scale = 1.0;
  // A jog may not expire later than this many seconds after it arrives.
  double max_jog_duration = 10.0;
  size_t max_trajectory_id_length = 128;
  Eigen::VectorXd true_joint_offsets;  // empty: the true model is the nominal one
  // A measured joint beyond a limit by more than this (rad or m) latches a fault; less is
  // rounding and is clamped silently.
  double limit_fault_tolerance = 1e-9;
};

struct TrajectoryAcceptance {
  bool duplicate = false;         // the id had been accepted before; nothing new was executed
  core::TrajectoryRecord record;  // the record of that id (for a duplicate: its current status)
};

class SimulatedRobot {
 public:
  // Fails with a message naming the option when the options are invalid. The clock's now()
  // at this call is the robot's time zero point.
  static Result<std::unique_ptr<SimulatedRobot>> create(core::RobotModelPtr model,
                                                        std::shared_ptr<const SimClock> clock,
                                                        SimulatedRobotOptions options = {});

  SimulatedRobot(const SimulatedRobot&) = delete;
  SimulatedRobot& operator=(const SimulatedRobot&) = delete;

  const core::RobotModelPtr& model() const { return model_; }  // nominal: what q is measured in
  const core::RobotModelPtr& true_model() const { return true_model_; }
  const SimulatedRobotOptions& options() const { return options_; }

  // Integrates every whole servo period up to clock->now().
  void update();
  // A snapshot as of the last update() or command; it does not integrate.
  core::RobotState state() const;
  double time() const;  // the robot's time, s
  std::optional<core::TrajectoryRecord> trajectory_record(const std::string& id) const;

  // Jogs at joint velocity qd (dof values, each within its max velocity) until expires_at
  // (robot time, s), then stops. Rejected when expired on arrival, when the e-stop is engaged
  // or a trajectory is running.
  Status jog_velocity(const Eigen::VectorXd& qd, double expires_at);
  // Jogs to the configuration core's apply_motion gives for `command` (see the header
  // comment for what it is applied to); the outcome carries the target and any singularity
  // warning. A rejected motion command's message is the error.
  Result<core::MotionOutcome> jog(const core::MotionCommand& command, double expires_at,
                                  const core::MotionOptions& motion_options = {});

  // Validates and starts a trajectory. An id is 1 to max_trajectory_id_length printable
  // ASCII characters. The arm must be idle (not jogging, stopping or running another one).
  Result<TrajectoryAcceptance> execute(const std::string& id, const core::Trajectory& trajectory);
  Result<TrajectoryAcceptance> execute(const std::string& id, core::TimedWaypoints waypoints);

  // Controlled stop of any jog or trajectory (and the gripper); `reason` is recorded with a
  // cancelled trajectory. A no-op when nothing moves or the e-stop is engaged.
  void cancel(const std::string& reason = "cancelled");

  // Moves the gripper to `opening` (0 closed .. 1 open) at options.gripper_speed.
  Status set_gripper(double opening);

  // Latched e-stop: every joint and the gripper halt at once; a running trajectory is
  // aborted. Engaging it again keeps the first reason.
  void estop(const std::string& reason = "e-stop");
  // Releases the e-stop; refused while any joint still moves (a drifting joint). A no-op when
  // the e-stop is not engaged. The servo then holds where the arm measured.
  Status reset_estop();

  // Clears the latched joint-limit fault message.
  void clear_fault();

  // Test hooks (telear/sim/joint_fault.hpp). One fault per joint; injecting replaces it.
  Status inject_fault(const JointFault& fault);
  // Removes every injected fault; only while the arm is idle or e-stopped. The servo then
  // holds where the arm measured.
  Status clear_injected_faults();

 private:
  enum class JogKind { kVelocity, kTarget };
  struct ActiveTrajectory {
    TrajectoryReference reference;
    std::string id;
    bool approaching = false;  // moving to the start; the trajectory's clock has not started
    double start_time = 0.0;   // robot time of the trajectory's t = 0
    size_t next_gripper_event = 0;
  };

  SimulatedRobot(core::RobotModelPtr model, core::RobotModelPtr true_model,
                 std::shared_ptr<const SimClock> clock, SimulatedRobotOptions options);

  // All below: the mutex is held.
  double now() const;
  void catch_up();
  void step();
  void step_trajectory(double t_next);
  void apply_gripper_events(double trajectory_time);
  void update_measured(double dt);
  void begin_stop(const std::string& reason, core::TrajectoryStatus trajectory_status);
  void finish_trajectory(core::TrajectoryStatus status, const std::string& message);
  void sync_command_to_measured();
  Status check_can_move(const char* what) const;
  Status check_jog_expiry(double expires_at) const;
  Result<TrajectoryAcceptance> start_trajectory(const std::string& id,
                                                Result<TrajectoryReference> reference);
  JointMotion commanded(int j) const { return {q_cmd_[j], qd_cmd_[j]}; }

  const core::RobotModelPtr model_;
  const core::RobotModelPtr true_model_;
  const std::shared_ptr<const SimClock> clock_;
  const SimulatedRobotOptions options_;
  std::vector<JointStepLimits> limits_;

  mutable std::mutex mutex_;
  double t0_ = 0.0;
  long long steps_ = 0;  // servo periods integrated since t0_
  core::RobotMode mode_ = core::RobotMode::kIdle;
  Eigen::VectorXd q_cmd_, qd_cmd_, q_, qd_;

  JogKind jog_kind_ = JogKind::kVelocity;
  Eigen::VectorXd jog_velocity_, jog_target_;
  double jog_expires_at_ = 0.0;

  Eigen::VectorXd stop_deceleration_;  // per joint, during a controlled stop
  std::string stop_reason_;

  std::optional<ActiveTrajectory> trajectory_;
  std::unordered_map<std::string, core::TrajectoryRecord> records_;
  Eigen::VectorXd sample_q_, sample_qd_;  // scratch, so stepping does not allocate

  double gripper_ = 1.0, gripper_target_ = 1.0;

  std::string estop_reason_;
  double estop_time_ = 0.0;
  std::optional<std::string> fault_;

  std::vector<std::optional<JointFault>> faults_;
  Eigen::VectorXd drift_offset_;
};

}  // namespace telear::sim
