#include "telear/net/robot_command_validation.hpp"

#include <cmath>

#include "telear/core/clock.hpp"
#include "telear/core/joint_limits.hpp"
#include "telear/core/number_format.hpp"

namespace telear::net {

namespace {

// Values in refusals: four significant digits unless a field needs another form.
constexpr const char* kValue = "%.4g";

std::string milliseconds_tenths(std::int64_t ns) {
  return core::format_number(static_cast<double>(ns) * 1e-6, "%.1f") + " ms";
}

// "0.120 rad" or "0.0300 m": the value in SI units, as the wire carries it.
std::string si_value(const core::RobotModel& model, int joint, double value) {
  const bool prismatic = model.joint(joint).type == core::JointType::kPrismatic;
  return core::format_number(value, prismatic ? "%.4f" : "%.3f") + (prismatic ? " m" : " rad");
}

template <typename Repeated>
Result<Eigen::VectorXd> finite_vector(const Repeated& values, int size, const std::string& what) {
  if (values.size() != size) {
    return Error{what + " has " + std::to_string(values.size()) + " values, expected " +
                 std::to_string(size)};
  }
  Eigen::VectorXd v(size);
  for (int i = 0; i < size; ++i) {
    if (!std::isfinite(values[i])) {
      return Error{what + "[" + std::to_string(i) +
                   "] is not a finite number: " + core::format_number(values[i], kValue)};
    }
    v[i] = values[i];
  }
  return v;
}

Result<Eigen::Vector3d> finite_vector3(const google::protobuf::RepeatedField<double>& values,
                                       const std::string& what) {
  auto v = finite_vector(values, 3, what);
  if (!v) return v.error();
  return Eigen::Vector3d(*v);
}

core::MotionFrame frame_from_proto(v1::MotionFrame frame) {
  switch (frame) {
    case v1::MOTION_FRAME_WRIST:
      return core::MotionFrame::kWrist;
    case v1::MOTION_FRAME_TOOL:
      return core::MotionFrame::kTool;
    default:
      return core::MotionFrame::kBase;
  }
}

}  // namespace

Status check_trajectory_id(const std::string& id, const CommandLimits& limits) {
  if (id.empty()) return Error{"trajectory rejected: its id is empty"};
  if (id.size() > limits.max_trajectory_id_length) {
    return Error{"trajectory rejected: its id is " + std::to_string(id.size()) +
                 " characters long, more than the maximum of " +
                 std::to_string(limits.max_trajectory_id_length)};
  }
  for (const char c : id) {
    if (c < 0x20 || c > 0x7e) {
      return Error{"trajectory rejected: its id contains characters other than printable ASCII"};
    }
  }
  return Status::Ok();
}

Result<core::TimedWaypoints> timed_waypoints_from_request(
    const core::RobotModel& model, const v1::ExecuteTrajectoryRequest& request,
    const CommandLimits& limits) {
  const std::string label = "trajectory '" + request.trajectory_id() + "' rejected: ";
  const int n = request.waypoints_size();
  if (n == 0) return Error{label + "it has no waypoints"};
  if (n > limits.max_waypoints) {
    return Error{label + "it has " + std::to_string(n) + " waypoints, more than the maximum of " +
                 std::to_string(limits.max_waypoints)};
  }
  core::TimedWaypoints w;
  w.times.reserve(static_cast<size_t>(n));
  w.q.reserve(static_cast<size_t>(n));
  for (const v1::Waypoint& waypoint : request.waypoints()) {
    w.times.push_back(core::ns_to_s(waypoint.time_from_start_ns()));
    // Size and finiteness are checked by validate_timed_waypoints, with the sample's index.
    w.q.emplace_back(Eigen::Map<const Eigen::VectorXd>(waypoint.q().data(), waypoint.q_size()));
  }
  if (request.gripper_size() > n) {
    return Error{label + "it has " + std::to_string(request.gripper_size()) +
                 " gripper commands, more than its " + std::to_string(n) + " waypoints"};
  }
  for (const v1::GripperCommand& g : request.gripper()) {
    w.gripper.push_back(core::GripperEvent{core::ns_to_s(g.time_from_start_ns()), g.opening()});
  }
  core::TimedWaypointsLimits core_limits;
  core_limits.max_samples = limits.max_waypoints;
  if (Status s = core::validate_timed_waypoints(model, w, core_limits); !s) {
    return Error{label + s.error().message};
  }
  return w;
}

Status check_start_state(const core::RobotModel& model, const std::string& trajectory_id,
                         const Eigen::VectorXd& start, const Eigen::VectorXd& current_q,
                         double tolerance) {
  Eigen::Index worst = 0;
  const double deviation = (start - current_q).cwiseAbs().maxCoeff(&worst);
  if (deviation <= tolerance) return Status::Ok();
  const int j = static_cast<int>(worst);
  return Error{"trajectory '" + trajectory_id + "' rejected: it starts " +
               si_value(model, j, deviation) + " (" +
               core::format_joint_value(model, j, deviation) + ") from the current state at " +
               core::joint_label(model, j) + " (tolerance " + si_value(model, j, tolerance) +
               "): the arm is at " + si_value(model, j, current_q[j]) +
               ", the trajectory starts at " + si_value(model, j, start[j])};
}

Result<JogCommand> jog_command_from_request(const core::RobotModel& model,
                                            const v1::JogRequest& request) {
  const int dof = model.dof();
  JogCommand jog;
  switch (request.command_case()) {
    case v1::JogRequest::kJointIncrement: {
      const auto& inc = request.joint_increment();
      if (inc.joint() < 0 || inc.joint() >= dof) {
        return Error{"jog rejected: joint index " + std::to_string(inc.joint()) +
                     " is out of range (0-based, the robot has " + std::to_string(dof) +
                     " joints)"};
      }
      if (!std::isfinite(inc.delta())) {
        return Error{"jog rejected: the increment is not a finite number: " +
                     core::format_number(inc.delta(), kValue)};
      }
      jog.motion = core::JointIncrement{inc.joint(), inc.delta()};
      jog.description = "joint increment: " + core::joint_label(model, inc.joint()) + " by " +
                        si_value(model, inc.joint(), inc.delta());
      return jog;
    }
    case v1::JogRequest::kJointTarget: {
      auto q = finite_vector(request.joint_target().q(), dof, "joint target q");
      if (!q) return Error{"jog rejected: " + q.error().message};
      jog.motion = core::JointTarget{*q};
      jog.description = "joint target";
      return jog;
    }
    case v1::JogRequest::kCartesianIncrement: {
      const auto& inc = request.cartesian_increment();
      auto dX = finite_vector3(inc.translation_m(), "translation_m");
      if (!dX) return Error{"jog rejected: " + dX.error().message};
      auto dM = finite_vector3(inc.rotation_rad(), "rotation_rad");
      if (!dM) return Error{"jog rejected: " + dM.error().message};
      const core::MotionFrame frame = frame_from_proto(inc.frame());
      jog.motion = core::CartesianIncrement{frame, *dX, *dM};
      jog.description = std::string("Cartesian increment in the ") + to_string(frame) +
                        " frame: " + core::format_number(dX->norm(), kValue) + " m, " +
                        core::format_number(dM->norm(), kValue) + " rad";
      return jog;
    }
    case v1::JogRequest::kCartesianTarget: {
      const auto& target = request.cartesian_target();
      auto X = finite_vector3(target.position_m(), "position_m");
      if (!X) return Error{"jog rejected: " + X.error().message};
      auto M = finite_vector3(target.rotation_rad(), "rotation_rad");
      if (!M) return Error{"jog rejected: " + M.error().message};
      jog.motion = core::cartesian_target(*X, *M);
      jog.description = "Cartesian target";
      return jog;
    }
    case v1::JogRequest::kJointVelocity: {
      auto qd = finite_vector(request.joint_velocity().qd(), dof, "joint velocity qd");
      if (!qd) return Error{"jog rejected: " + qd.error().message};
      jog.velocity = *qd;
      jog.description = "joint velocity";
      return jog;
    }
    case v1::JogRequest::COMMAND_NOT_SET:
      break;
  }
  return Error{"jog rejected: it carries no command"};
}

Status check_jog_expiry(std::int64_t expires_ns, std::int64_t now_ns, const CommandLimits& limits) {
  if (expires_ns <= now_ns) {
    return Error{"jog ignored: it expired " + milliseconds_tenths(now_ns - expires_ns) +
                 " before it arrived (expires_ns is on the server's clock; see Ping)"};
  }
  if (expires_ns - now_ns > limits.max_jog_duration_ns) {
    return Error{"jog rejected: it expires " + milliseconds_tenths(expires_ns - now_ns) +
                 " from now, later than the maximum of " +
                 milliseconds_tenths(limits.max_jog_duration_ns)};
  }
  return Status::Ok();
}

Status check_ghost(const core::RobotModel& model, const Eigen::VectorXd& q, double gripper) {
  if (q.size() != model.dof()) {
    return Error{"ghost rejected: " + std::to_string(q.size()) + " joint values for a " +
                 std::to_string(model.dof()) + "-joint arm"};
  }
  if (!q.allFinite()) return Error{"ghost rejected: a joint value is not a finite number"};
  if (const auto violation = core::first_limit_violation(model, q)) {
    return Error{"ghost rejected: " + core::describe_violation(model, *violation)};
  }
  if (!(std::isfinite(gripper) && gripper >= 0.0 && gripper <= 1.0)) {
    return Error{"ghost rejected: gripper opening " + core::format_number(gripper, kValue) +
                 " is outside [0, 1]"};
  }
  return Status::Ok();
}

Status check_gripper_opening(double opening) {
  if (!(std::isfinite(opening) && opening >= 0.0 && opening <= 1.0)) {
    return Error{"gripper command rejected: opening " + core::format_number(opening, kValue) +
                 " is outside [0, 1] (0 closed, 1 open)"};
  }
  return Status::Ok();
}

}  // namespace telear::net
