#include "telear/core/kinematics.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>

#include "telear/core/fast_sincos.hpp"

namespace telear::core {
namespace {

// ---- rigid transforms in SIMD lane pairs ----------------------------------------------------
//
// A frame is kept as the top three rows of its homogeneous matrix, column by column in the
// layout of Eigen's column-major Isometry3d::matrix(): each column's rows 0 and 1 in one lane
// pair (one SSE2 register), row 2 as a scalar. Products are written by hand on these columns,
// without Eigen temporaries. The bottom row (0 0 0 1) is never computed: the frames in
// KinematicsData are constructed as identities and only their top three rows are written.
struct Frame {
  Double2 x, y, z, p;     // rows 0, 1 of the rotation columns and of the origin
  double x2, y2, z2, p2;  // row 2
};
static_assert(!(Eigen::Isometry3d::MatrixType::Flags & Eigen::RowMajorBit),
              "load() / store() assume Eigen's default column-major storage");

inline Double2 load2(const double* m) {
  Double2 v;
  std::memcpy(&v, m, sizeof v);
  return v;
}

inline void store2(double* m, const Double2& v) {
  std::memcpy(m, &v, sizeof v);
}

inline Double2 splat(double v) {
  return Double2{v, v};
}

inline Frame load(const Eigen::Isometry3d& T) {
  const double* m = T.matrix().data();
  return {load2(m), load2(m + 4), load2(m + 8), load2(m + 12), m[2], m[6], m[10], m[14]};
}

inline Frame identity_frame() {
  const Double2 zero = {0.0, 0.0};
  return {Double2{1.0, 0.0}, Double2{0.0, 1.0}, zero, zero, 0.0, 0.0, 1.0, 0.0};
}

inline void store(const Frame& F, Eigen::Isometry3d& T) {
  double* m = T.matrix().data();
  store2(m, F.x);
  m[2] = F.x2;
  store2(m + 4, F.y);
  m[6] = F.y2;
  store2(m + 8, F.z);
  m[10] = F.z2;
  store2(m + 12, F.p);
  m[14] = F.p2;
}

// Exact comparison with the identity (top three rows).
inline bool is_identity(const Frame& F) {
  const Double2 zero = {0.0, 0.0};
  const auto equal =
      (F.x == Double2{1.0, 0.0}) & (F.y == Double2{0.0, 1.0}) & (F.z == zero) & (F.p == zero);
  return equal[0] != 0 && equal[1] != 0 && F.x2 == 0.0 && F.y2 == 0.0 && F.z2 == 1.0 && F.p2 == 0.0;
}

// A * B.
inline Frame compose(const Frame& A, const Frame& B) {
  Frame out;
  auto column = [&A](const Double2& b01, double b2, Double2& o01, double& o2) {
    o01 = b01[0] * A.x + b01[1] * A.y + b2 * A.z;
    o2 = b01[0] * A.x2 + b01[1] * A.y2 + b2 * A.z2;
  };
  column(B.x, B.x2, out.x, out.x2);
  column(B.y, B.y2, out.y, out.y2);
  column(B.z, B.z2, out.z, out.z2);
  column(B.p, B.p2, out.p, out.p2);
  out.p = out.p + A.p;
  out.p2 = out.p2 + A.p2;
  return out;
}

// The joint motion Z(v): a rotation about z by v (given its cos and sin) or a translation
// along z by v.
inline Frame joint_motion(JointType type, double c, double s, double v) {
  Frame Z = identity_frame();
  if (type == JointType::kRevolute) {
    Z.x = Double2{c, s};
    Z.y = Double2{-s, c};
  } else {
    Z.p2 = v;
  }
  return Z;
}

// Frame i-1 * before_i: the frame joint i's axis is the z axis of (current is frame i-1).
inline Frame joint_frame(const Joint& joint, const Frame& current) {
  return joint.before_is_identity ? current : compose(current, load(joint.before));
}

// The DH parameters a joint of a kDh* form reads from after = Tz(d) Tx(a) Rx(alpha).
struct DhParameters {
  double a, d, c_alpha, s_alpha;
};

inline DhParameters dh_parameters(const Joint& joint) {
  const Eigen::Matrix4d& A = joint.after.matrix();
  return {A(0, 3), A(2, 3), A(1, 1), A(2, 1)};
}

// T * Rz(theta) Tz(d) Tx(a) Rx(alpha), one standard-DH joint, given c, s = cos, sin theta.
// With T's columns [x y z p]: Rz turns the axes into x' = c x + s y and y' = c y - s x;
// Rx(alpha) gives y'' = c_alpha y' + s_alpha z and z'' = c_alpha z - s_alpha y', which for the
// twists of a real arm is a copy or a negation: alpha = 0: (y', z); +pi/2: (z, -y');
// -pi/2: (-z, y'). The origin moves by a along x' and d along z. Terms with a or d exactly 0
// are skipped (they would add exact zeros). 2 to 4 column products instead of the 12 + 12
// of forming the joint's transform and multiplying by it.
inline Frame dh_step(JointForm form, const Frame& T, double c, double s, const DhParameters& dh) {
  const Double2 vc = splat(c), vs = splat(s);
  Frame out;
  out.x = vc * T.x + vs * T.y;
  out.x2 = c * T.x2 + s * T.y2;
  switch (form) {
    case JointForm::kDhTwist0:
      out.y = vc * T.y - vs * T.x;
      out.y2 = c * T.y2 - s * T.x2;
      out.z = T.z;
      out.z2 = T.z2;
      break;
    case JointForm::kDhTwistPlus90: {  // s_alpha = 1: y'' = c_alpha y' + z, z'' = c_alpha z - y'
      const Double2 y = vc * T.y - vs * T.x;
      const double y2 = c * T.y2 - s * T.x2;
      out.y = dh.c_alpha * y + T.z;
      out.y2 = dh.c_alpha * y2 + T.z2;
      out.z = dh.c_alpha * T.z - y;
      out.z2 = dh.c_alpha * T.z2 - y2;
      break;
    }
    case JointForm::kDhTwistMinus90: {  // s_alpha = -1
      const Double2 y = vc * T.y - vs * T.x;
      const double y2 = c * T.y2 - s * T.x2;
      out.y = dh.c_alpha * y - T.z;
      out.y2 = dh.c_alpha * y2 - T.z2;
      out.z = dh.c_alpha * T.z + y;
      out.z2 = dh.c_alpha * T.z2 + y2;
      break;
    }
    default: {
      const Double2 y = vc * T.y - vs * T.x;
      const double y2 = c * T.y2 - s * T.x2;
      out.y = dh.c_alpha * y + dh.s_alpha * T.z;
      out.y2 = dh.c_alpha * y2 + dh.s_alpha * T.z2;
      out.z = dh.c_alpha * T.z - dh.s_alpha * y;
      out.z2 = dh.c_alpha * T.z2 - dh.s_alpha * y2;
    }
  }
  out.p = T.p;
  out.p2 = T.p2;
  if (dh.a != 0.0) {
    out.p = out.p + dh.a * out.x;
    out.p2 = out.p2 + dh.a * out.x2;
  }
  if (dh.d != 0.0) {
    out.p = out.p + dh.d * T.z;
    out.p2 = out.p2 + dh.d * T.z2;
  }
  return out;
}

// The same step from the base frame (the identity), where every product is known: frame 1 is
// the joint's own transform. Used for joint 0, whose parent frame is always the base.
inline Frame dh_first(JointForm form, double c, double s, const DhParameters& dh) {
  const Double2 zero = {0.0, 0.0};
  Frame out;
  out.x = Double2{c, s};
  out.x2 = 0.0;
  switch (form) {
    case JointForm::kDhTwist0:
      out.y = Double2{-s, c};
      out.y2 = 0.0;
      out.z = zero;
      out.z2 = 1.0;
      break;
    default:
      out.y = Double2{-s * dh.c_alpha, c * dh.c_alpha};
      out.y2 = dh.s_alpha;
      out.z = Double2{s * dh.s_alpha, -c * dh.s_alpha};
      out.z2 = dh.c_alpha;
  }
  out.p = dh.a * out.x;
  out.p2 = dh.d;
  return out;
}

// Re-computes link frames first_joint+1..n and the tool from frame first_joint.
//
// Joints of a DH form (JointForm, classified by RobotModel::create) take dh_step. Any other
// joint multiplies by before * Z(q + offset) * after. The sines and cosines of a block of joints
// are evaluated first, two at a time, so that the chain of frame products then runs without waiting
// on them.
void propagate(const RobotModel& model, KinematicsData& data, int first_joint) {
  const int n = model.dof();
  constexpr int kBlock = 8;  // even: sincos2 takes pairs
  alignas(16) double angles[kBlock], sines[kBlock], cosines[kBlock];
  Frame current = first_joint == 0 ? identity_frame()
                                   : load(data.T_base_link[static_cast<size_t>(first_joint)]);
  for (int start = first_joint; start < n; start += kBlock) {
    const int count = std::min(kBlock, n - start);
    for (int k = 0; k < count; ++k) angles[k] = data.q[start + k] + model.joint(start + k).offset;
    if (count % 2 != 0) angles[count] = 0.0;
    for (int k = 0; k < count; k += 2) {
      Double2 s, c;
      sincos2(load2(angles + k), s, c);
      store2(sines + k, s);
      store2(cosines + k, c);
    }
    for (int k = 0; k < count; ++k) {
      const int i = start + k;
      const auto index = static_cast<size_t>(i);
      const Joint& joint = model.joint(i);
      const double c = cosines[k], s = sines[k];
      if (joint.form != JointForm::kGeneral) {
        current = i == 0 ? dh_first(joint.form, c, s, dh_parameters(joint))
                         : dh_step(joint.form, current, c, s, dh_parameters(joint));
      } else {
        const Frame local = compose(joint_motion(joint.type, c, s, angles[k]), load(joint.after));
        current = compose(joint_frame(joint, current), local);
      }
      store(current, data.T_base_link[index + 1]);
    }
  }
  const Frame tool = load(model.T_flange_tool());
  store(is_identity(tool) ? current : compose(current, tool), data.T_base_tool);
  data.last_first_updated_joint = first_joint;
  data.last_frames_recomputed = n - first_joint;
}

}  // namespace

KinematicsData::KinematicsData(const RobotModel& model)
    : q(Eigen::VectorXd::Zero(model.dof())),
      T_base_link(static_cast<size_t>(model.dof()) + 1, Eigen::Isometry3d::Identity()),
      T_base_tool(Eigen::Isometry3d::Identity()) {}

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
    // Joint i's axis z and a point o on it, in the base frame, as forward kinematics saw them.
    const Joint& joint = model.joint(i);
    const Frame F = joint_frame(joint, load(data.T_base_link[static_cast<size_t>(i)]));
    const Eigen::Vector3d z(F.z[0], F.z[1], F.z2);
    const Eigen::Vector3d o(F.p[0], F.p[1], F.p2);
    if (joint.type == JointType::kRevolute) {
      J.block<3, 1>(0, i) = z.cross(p_tool - o);
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

}  // namespace telear::core
