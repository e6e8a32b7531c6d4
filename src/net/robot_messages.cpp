#include "telear/net/robot_messages.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <type_traits>
#include <variant>

#include "telear/core/clock.hpp"

namespace telear::net {

namespace {

void copy(const Eigen::VectorXd& v, google::protobuf::RepeatedField<double>* out) {
  out->Assign(v.data(), v.data() + v.size());
}

Eigen::VectorXd vector(const google::protobuf::RepeatedField<double>& values) {
  return Eigen::Map<const Eigen::VectorXd>(values.data(), values.size());
}

}  // namespace

v1::RobotMode to_proto(core::RobotMode mode) {
  switch (mode) {
    case core::RobotMode::kIdle:
      return v1::ROBOT_MODE_IDLE;
    case core::RobotMode::kJogging:
      return v1::ROBOT_MODE_JOGGING;
    case core::RobotMode::kTrajectory:
      return v1::ROBOT_MODE_TRAJECTORY;
    case core::RobotMode::kStopping:
      return v1::ROBOT_MODE_STOPPING;
    case core::RobotMode::kEStopped:
      return v1::ROBOT_MODE_ESTOPPED;
  }
  return v1::ROBOT_MODE_UNSPECIFIED;
}

core::RobotMode from_proto(v1::RobotMode mode) {
  switch (mode) {
    case v1::ROBOT_MODE_JOGGING:
      return core::RobotMode::kJogging;
    case v1::ROBOT_MODE_TRAJECTORY:
      return core::RobotMode::kTrajectory;
    case v1::ROBOT_MODE_STOPPING:
      return core::RobotMode::kStopping;
    case v1::ROBOT_MODE_ESTOPPED:
      return core::RobotMode::kEStopped;
    default:
      return core::RobotMode::kIdle;
  }
}

v1::TrajectoryStatus to_proto(core::TrajectoryStatus status) {
  switch (status) {
    case core::TrajectoryStatus::kRunning:
      return v1::TRAJECTORY_STATUS_RUNNING;
    case core::TrajectoryStatus::kCompleted:
      return v1::TRAJECTORY_STATUS_COMPLETED;
    case core::TrajectoryStatus::kCancelled:
      return v1::TRAJECTORY_STATUS_CANCELLED;
    case core::TrajectoryStatus::kAborted:
      return v1::TRAJECTORY_STATUS_ABORTED;
  }
  return v1::TRAJECTORY_STATUS_UNSPECIFIED;
}

core::TrajectoryStatus from_proto(v1::TrajectoryStatus status) {
  switch (status) {
    case v1::TRAJECTORY_STATUS_COMPLETED:
      return core::TrajectoryStatus::kCompleted;
    case v1::TRAJECTORY_STATUS_CANCELLED:
      return core::TrajectoryStatus::kCancelled;
    case v1::TRAJECTORY_STATUS_ABORTED:
      return core::TrajectoryStatus::kAborted;
    default:
      return core::TrajectoryStatus::kRunning;
  }
}

void fill_model_info(const core::RobotModel& model, v1::RobotInfo& info) {
  info.set_model_name(model.name());
  for (const core::Joint& joint : model.joints()) {
    v1::JointInfo* j = info.add_joints();
    j->set_name(joint.name);
    j->set_prismatic(joint.type == core::JointType::kPrismatic);
    j->set_min_position(joint.limits.lower);
    j->set_max_position(joint.limits.upper);
    j->set_max_velocity(joint.limits.max_velocity);
    j->set_max_acceleration(joint.limits.max_acceleration);
  }
  for (const core::NamedConfiguration& named : model.named_configurations()) {
    v1::NamedConfiguration* c = info.add_named_configurations();
    c->set_name(named.name);
    copy(named.q, c->mutable_q());
  }
}

void fill_state(const core::RobotState& state, v1::RobotState& message) {
  message.set_mode(to_proto(state.mode));
  copy(state.q, message.mutable_q());
  copy(state.qd, message.mutable_qd());
  copy(state.q_commanded, message.mutable_q_commanded());
  message.set_gripper_opening(state.gripper);
  message.set_gripper_target(state.gripper_target);
  message.set_estop(state.estop);
  message.set_estop_reason(state.estop_reason);
  message.set_trajectory_id(state.trajectory_id);
  message.set_trajectory_progress(state.trajectory_progress);
  message.set_trajectory_time_s(state.trajectory_time);
  message.set_trajectory_duration_s(state.trajectory_duration);
  message.set_fault(state.fault.value_or(""));
  message.set_stop_reason(state.stop_reason);
}

core::RobotState state_from_proto(const v1::RobotState& message) {
  core::RobotState state;
  state.time = core::ns_to_s(message.capture_ns());
  state.mode = from_proto(message.mode());
  state.q = vector(message.q());
  state.qd = vector(message.qd());
  state.q_commanded = vector(message.q_commanded());
  state.qd_commanded = state.qd;  // not on the wire; the measured velocity stands in
  state.gripper = message.gripper_opening();
  state.gripper_target = message.gripper_target();
  state.gripper_moving = state.gripper != state.gripper_target;
  state.estop = message.estop();
  state.estop_reason = message.estop_reason();
  state.trajectory_id = message.trajectory_id();
  state.trajectory_time = message.trajectory_time_s();
  state.trajectory_duration = message.trajectory_duration_s();
  state.trajectory_progress = message.trajectory_progress();
  state.stop_reason = message.stop_reason();
  if (!message.fault().empty()) state.fault = message.fault();
  return state;
}

void fill_jog_request(const core::MotionCommand& command, v1::JogRequest& request) {
  std::visit(
      [&request](const auto& c) {
        using T = std::decay_t<decltype(c)>;
        if constexpr (std::is_same_v<T, core::JointIncrement>) {
          request.mutable_joint_increment()->set_joint(c.joint);
          request.mutable_joint_increment()->set_delta(c.delta);
        } else if constexpr (std::is_same_v<T, core::JointTarget>) {
          copy(c.q, request.mutable_joint_target()->mutable_q());
        } else if constexpr (std::is_same_v<T, core::CartesianIncrement>) {
          auto* inc = request.mutable_cartesian_increment();
          inc->set_frame(c.frame == core::MotionFrame::kWrist  ? v1::MOTION_FRAME_WRIST
                         : c.frame == core::MotionFrame::kTool ? v1::MOTION_FRAME_TOOL
                                                               : v1::MOTION_FRAME_BASE);
          inc->mutable_translation_m()->Assign(c.dX.data(), c.dX.data() + 3);
          inc->mutable_rotation_rad()->Assign(c.dM.data(), c.dM.data() + 3);
        } else {
          const Eigen::Vector3d X = c.T_base_tool.translation();
          const Eigen::AngleAxisd aa(c.T_base_tool.rotation());
          const Eigen::Vector3d M = aa.axis() * aa.angle();
          auto* target = request.mutable_cartesian_target();
          target->mutable_position_m()->Assign(X.data(), X.data() + 3);
          target->mutable_rotation_rad()->Assign(M.data(), M.data() + 3);
        }
      },
      command);
}

void fill_trajectory_request(const std::string& trajectory_id,
                             const core::TimedWaypoints& waypoints,
                             v1::ExecuteTrajectoryRequest& request) {
  request.set_trajectory_id(trajectory_id);
  const size_t n = std::min(waypoints.times.size(), waypoints.q.size());
  for (size_t k = 0; k < n; ++k) {
    v1::Waypoint* w = request.add_waypoints();
    w->set_time_from_start_ns(std::llround(waypoints.times[k] * 1e9));
    copy(waypoints.q[k], w->mutable_q());
  }
  for (const core::GripperEvent& event : waypoints.gripper) {
    v1::GripperCommand* g = request.add_gripper();
    g->set_time_from_start_ns(std::llround(event.time * 1e9));
    g->set_opening(event.opening);
  }
}

}  // namespace telear::net
