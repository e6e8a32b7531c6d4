#pragma once
// RobotDriver: what the robot server commands. The server is the safety authority (it
// authenticates, holds the lease, validates every command against the model and the current
// state); the driver moves the arm and keeps its own last line of defence (the simulated
// robot re-validates everything it is given).
//
// Time. The server works on the monotonic clock in nanoseconds (telear/core/clock.hpp): jog
// expiries arrive in it, state snapshots and acceptances are stamped in it. A driver with a clock
// of its own (the simulated robot counts seconds from its start) converts in one place, inside the
// driver, so no caller ever sees driver time.
//
// Thread safety: every member function may be called from any thread (the server calls from
// its RPC threads and the lease watchdog at once).

#include <cstdint>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "telear/core/motion_command.hpp"
#include "telear/core/result.hpp"
#include "telear/core/robot_model.hpp"
#include "telear/core/robot_state.hpp"
#include "telear/core/trajectory.hpp"
#include "telear/core/workspace.hpp"

namespace telear::core {

// A state snapshot and when it was taken (server clock).
struct DriverSnapshot {
  RobotState state;  // joint vectors dof() long; `time` is driver time, for display only
  std::int64_t capture_ns = 0;
};

// The answer to execute(): a new acceptance, or the first one of an id seen before.
struct DriverAcceptance {
  bool duplicate = false;
  TrajectoryRecord record;  // for a duplicate: the record's current status
  std::int64_t accepted_ns = 0;
};

class RobotDriver {
 public:
  virtual ~RobotDriver() = default;

  virtual const RobotModelPtr& model() const = 0;
  virtual std::string name() const = 0;                // "simulated", shown in GetInfo
  virtual std::string urdf() const = 0;                // the robot's URDF text, empty when unknown
  virtual std::string tip_link() const { return {}; }  // the URDF link the chain ends at
  virtual double start_tolerance() const = 0;          // rad or m, a trajectory's start vs the arm

  virtual DriverSnapshot snapshot() const = 0;
  virtual std::optional<TrajectoryRecord> trajectory_record(const std::string& id) const = 0;

  // Jogs; the arm makes a controlled stop at expires_ns (server clock). Rejected, with no
  // motion, when already expired, when the e-stop is engaged or a trajectory runs.
  virtual Result<MotionOutcome> jog(const MotionCommand& command, std::int64_t expires_ns) = 0;
  virtual Status jog_velocity(const Eigen::VectorXd& qd, std::int64_t expires_ns) = 0;
  // Starts a sampled trajectory; an id accepted before is answered with that acceptance.
  virtual Result<DriverAcceptance> execute(const std::string& id,
                                           const TimedWaypoints& waypoints) = 0;
  // A controlled stop of any jog or trajectory (Cancel, a lapsed lease); a running
  // trajectory is recorded as cancelled with `reason`. A no-op at rest or e-stopped.
  virtual void stop(const std::string& reason) = 0;
  virtual Status set_gripper(double opening) = 0;
  // Latched: halts at once; engaging again keeps the first reason.
  virtual void estop(const std::string& reason) = 0;
  virtual Status reset_estop() = 0;

  // What the operator rehearses, for a driver that can show it to the arm's own tools (the
  // ROS driver publishes it for RViz, docs/ros.md); nothing by default. The server calls
  // show_preview after each PreviewPlan it answered (the samples ExecutePlan would run),
  // show_ghost with the operator's ghost as the lease's heartbeat carries it, and
  // show_workspace once with the workspace it checks motions against. Must not block.
  virtual void show_preview(const std::string& /*plan_id*/, const TimedWaypoints& /*samples*/) {}
  // The lease holder's ghost, with each lease renewal that carries it (validated: dof finite
  // values within the limits, the opening in [0, 1]).
  virtual void show_ghost(const Eigen::VectorXd& /*q*/, double /*gripper*/) {}
  virtual void show_workspace(const Workspace& /*workspace*/) {}
};

}  // namespace telear::core
