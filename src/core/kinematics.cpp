#include "core/kinematics.hpp"

#include <cassert>
#include <cmath>
#include <sstream>

namespace telear {
namespace {

// M <- M * Rz(theta), touching only the first two rotation columns.
inline void post_rotate_z(Eigen::Isometry3d& M, double theta) {
  const double c = std::cos(theta);
  const double s = std::sin(theta);
  auto L = M.linear();
  const Eigen::Vector3d x = L.col(0);
  const Eigen::Vector3d y = L.col(1);
  L.col(0) = c * x + s * y;
  L.col(1) = c * y - s * x;
}

// Re-computes link frames first_joint+1..n and the tool from frame first_joint.
void propagate(const RobotModel& model, KinematicsData& data, int first_joint) {
  const int n = model.dof();
  for (int i = first_joint; i < n; ++i) {
    const Joint& joint = model.joint(i);
    const double value = data.q[i] + joint.offset;
    Eigen::Isometry3d M = data.T_base_link[static_cast<size_t>(i)];
    if (!joint.before_is_identity) M = M * joint.before;
    if (joint.type == JointType::kRevolute) {
      post_rotate_z(M, value);
    } else {
      M.translation() += value * M.linear().col(2);
    }
    data.axis_base[static_cast<size_t>(i)] = M.linear().col(2);
    data.axis_origin_base[static_cast<size_t>(i)] = M.translation();
    data.T_base_link[static_cast<size_t>(i) + 1] = joint.after_is_identity ? M : M * joint.after;
  }
  data.T_base_tool = data.T_base_link[static_cast<size_t>(n)] * model.T_flange_tool();
  data.last_first_updated_joint = first_joint;
  data.last_frames_recomputed = n - first_joint;
}

}  // namespace

KinematicsData::KinematicsData(const RobotModel& model)
    : q(Eigen::VectorXd::Zero(model.dof())),
      T_base_link(static_cast<size_t>(model.dof()) + 1, Eigen::Isometry3d::Identity()),
      T_base_tool(Eigen::Isometry3d::Identity()),
      axis_base(static_cast<size_t>(model.dof()), Eigen::Vector3d::UnitZ()),
      axis_origin_base(static_cast<size_t>(model.dof()), Eigen::Vector3d::Zero()) {}

void forward_kinematics(const RobotModel& model, KinematicsData& data, const Eigen::VectorXd& q) {
  assert(q.size() == model.dof() && "forward_kinematics(): wrong joint vector size");
  data.q = q;
  propagate(model, data, 0);
  data.valid = true;
}

void set_joint(const RobotModel& model, KinematicsData& data, int joint, double value) {
  assert(joint >= 0 && joint < model.dof() && "set_joint(): joint index out of range");
  if (!data.valid) {
    data.q[joint] = value;
    forward_kinematics(model, data, data.q);
    return;
  }
  data.q[joint] = value;
  propagate(model, data, joint);
}

void update_kinematics(const RobotModel& model, KinematicsData& data, const Eigen::VectorXd& q) {
  assert(q.size() == model.dof() && "update_kinematics(): wrong joint vector size");
  if (!data.valid) {
    forward_kinematics(model, data, q);
    return;
  }
  int first = 0;
  const int n = model.dof();
  while (first < n && q[first] == data.q[first]) ++first;
  if (first == n) {
    data.last_first_updated_joint = n;
    data.last_frames_recomputed = 0;
    return;
  }
  data.q.tail(n - first) = q.tail(n - first);
  propagate(model, data, first);
}

void geometric_jacobian(const RobotModel& model, const KinematicsData& data, JacobianFrame frame,
                        Jacobian& J) {
  const int n = model.dof();
  J.resize(6, n);
  const Eigen::Vector3d p_tool = data.T_base_tool.translation();
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d& z = data.axis_base[static_cast<size_t>(i)];
    if (model.joint(i).type == JointType::kRevolute) {
      J.block<3, 1>(0, i) = z.cross(p_tool - data.axis_origin_base[static_cast<size_t>(i)]);
      J.block<3, 1>(3, i) = z;
    } else {
      J.block<3, 1>(0, i) = z;
      J.block<3, 1>(3, i).setZero();
    }
  }
  if (frame == JacobianFrame::kTool) {
    const Eigen::Matrix3d R_tool_base = data.T_base_tool.linear().transpose();
    J.topRows<3>() = R_tool_base * J.topRows<3>();
    J.bottomRows<3>() = R_tool_base * J.bottomRows<3>();
  }
}

Eigen::Isometry3d tool_pose(const RobotModel& model, const Eigen::VectorXd& q) {
  KinematicsData data(model);
  forward_kinematics(model, data, q);
  return data.T_base_tool;
}

Status check_joint_vector(const RobotModel& model, const Eigen::VectorXd& q) {
  if (q.size() != model.dof()) {
    std::ostringstream s;
    s << "wrong number of joint values for robot '" << model.name() << "': expected " << model.dof()
      << ", got " << q.size();
    return Error{s.str()};
  }
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    if (!std::isfinite(q[i])) {
      std::ostringstream s;
      s << "joint " << (i + 1) << " (" << model.joint(static_cast<int>(i)).name
        << ") value is not a finite number: " << q[i];
      return Error{s.str()};
    }
  }
  return Status::Ok();
}

}  // namespace telear
