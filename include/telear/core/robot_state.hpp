#pragma once
// What the simulated robot reports: a snapshot of its state, taken by value under the
// robot's lock (the robot server streams it, the monitor compares it), and the record of
// every trajectory it accepted.
//
// Joint vectors are dof() long, rad and rad/s (revolute) or m and m/s (prismatic). q and qd
// are the measured joint readings in the *nominal* model; q_commanded and qd_commanded are
// what the servo was told. With an ideal servo they are equal; they differ only while a fault
// is injected (telear/sim/joint_fault.hpp), which is what an execution monitor looks for.

#include <Eigen/Core>
#include <optional>
#include <string>

namespace telear::core {

enum class RobotMode {
  kIdle,        // at rest, holding position
  kJogging,     // following a jog (a joint velocity, or a target from a motion command)
  kTrajectory,  // following a trajectory (or moving the last bit to its start)
  kStopping,    // a controlled stop: every joint decelerating to rest
  kEStopped,    // latched e-stop: halted, commands rejected until reset
};

const char* to_string(RobotMode mode);

enum class TrajectoryStatus {
  kRunning,
  kCompleted,
  kCancelled,  // stopped by cancel() (or the server, e.g. a lapsed lease)
  kAborted,    // stopped by the e-stop or a joint-limit fault
};

const char* to_string(TrajectoryStatus status);

struct TrajectoryRecord {
  std::string id;
  TrajectoryStatus status = TrajectoryStatus::kRunning;
  double accepted_at = 0.0;  // robot time, s
  double finished_at = 0.0;  // robot time, s; 0 while running
  double duration = 0.0;     // s, of the trajectory itself
  std::string message;       // why it was cancelled or aborted
};

struct RobotState {
  double time = 0.0;  // s on the robot's clock (a multiple of the servo period after start)
  RobotMode mode = RobotMode::kIdle;

  Eigen::VectorXd q, qd;                      // measured (nominal-model readings)
  Eigen::VectorXd q_commanded, qd_commanded;  // servo command

  double gripper = 0.0;         // opening, 0 closed .. 1 open
  double gripper_target = 0.0;  // where it is going, at the gripper's finite speed
  bool gripper_moving = false;

  bool estop = false;        // latched e-stop (mode kEStopped)
  std::string estop_reason;  // as given to estop()
  double estop_time = 0.0;   // robot time it was engaged

  std::string trajectory_id;         // the active trajectory, empty when none
  double trajectory_time = 0.0;      // s into it (0 while moving to its start)
  double trajectory_duration = 0.0;  // s
  double trajectory_progress = 0.0;  // trajectory_time / duration in [0, 1]

  double jog_expires_at = 0.0;  // robot time a running jog stops, 0 when not jogging
  std::string stop_reason;      // why the current controlled stop happens (mode kStopping)

  // Latched when the hard clamp at a joint limit had to act (says which joint and by how
  // much); cleared by SimulatedRobot::clear_fault().
  std::optional<std::string> fault;
};

}  // namespace telear::core
