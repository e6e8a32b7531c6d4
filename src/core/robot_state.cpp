#include "telear/core/robot_state.hpp"

namespace telear::core {

const char* to_string(RobotMode mode) {
  switch (mode) {
    case RobotMode::kIdle:
      return "idle";
    case RobotMode::kJogging:
      return "jogging";
    case RobotMode::kTrajectory:
      return "trajectory";
    case RobotMode::kStopping:
      return "stopping";
    case RobotMode::kEStopped:
      return "estopped";
  }
  return "?";
}

const char* to_string(TrajectoryStatus status) {
  switch (status) {
    case TrajectoryStatus::kRunning:
      return "running";
    case TrajectoryStatus::kCompleted:
      return "completed";
    case TrajectoryStatus::kCancelled:
      return "cancelled";
    case TrajectoryStatus::kAborted:
      return "aborted";
  }
  return "?";
}

}  // namespace telear::core
