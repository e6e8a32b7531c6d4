#include "telear/core/ik_ur.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "telear/core/angles.hpp"
#include "telear/core/joint_limits.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/number_format.hpp"

#include "ik_common.hpp"

namespace telear::core {
namespace {

// The class checks: directions (unit-vector products) and lengths.
constexpr double kGeometryTolerance = 1e-9;  // 1 or m
// Axes closer than this are one line: no upper arm / forearm.
constexpr double kMinLinkLength = 1e-6;  // m
// Below this sine, an angle decided by the directions of two projected vectors is undefined
// (the vectors are rounding noise): the joint takes its q_free value instead.
constexpr double kDegenerate = 1e-12;
// Newton polish of the labelled API: below this error (m, rad) a solution is left as it is.
constexpr double kPolishTolerance = 1e-12;
constexpr int kPolishSteps = 4;

// Rodrigues: v turned by the angle (c = cos, s = sin) about the unit axis k.
inline Eigen::Vector3d rotate(const Eigen::Vector3d& k, double c, double s,
                              const Eigen::Vector3d& v) {
  return c * v + s * k.cross(v) + ((1.0 - c) * k.dot(v)) * k;
}
inline Eigen::Vector3d rotate(const Eigen::Vector3d& k, double angle, const Eigen::Vector3d& v) {
  return rotate(k, std::cos(angle), std::sin(angle), v);
}

// The component of v perpendicular to the unit vector n.
inline Eigen::Vector3d across(const Eigen::Vector3d& n, const Eigen::Vector3d& v) {
  return v - n.dot(v) * n;
}

// Signed angle about the unit n from a to b (both perpendicular to n, or their projections).
inline double angle_about(const Eigen::Vector3d& n, const Eigen::Vector3d& a,
                          const Eigen::Vector3d& b) {
  return std::atan2(n.dot(a.cross(b)), a.dot(b));
}

// Angle between two unit vectors' lines (0 when parallel or opposite), for messages.
double line_angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), std::abs(a.dot(b)));
}

// Cosine and sine of the angle psi between the upper arm and the forearm when the far end is
// at distance `d` from the shoulder axis: d^2 = l2^2 + l3^2 + 2 l2 l3 cos psi. The sine from
// the triangle's area (Kahan's formula, accurate for needle-like triangles where acos of the
// cosine rule is not); d must lie in [|l2 - l3|, l2 + l3].
void elbow_angle(double l2, double l3, double d, double& c, double& s) {
  c = std::clamp((d * d - l2 * l2 - l3 * l3) / (2.0 * l2 * l3), -1.0, 1.0);
  double x = l2, y = l3, z = d;  // sort x >= y >= z
  if (x < y) std::swap(x, y);
  if (y < z) std::swap(y, z);
  if (x < y) std::swap(x, y);
  const double product = (x + (y + z)) * (z - (x - y)) * (z + (x - y)) * (x + (y - z));
  const double area = 0.25 * std::sqrt(std::max(0.0, product));
  s = 2.0 * area / (l2 * l3);
  const double norm = std::sqrt(c * c + s * s);
  if (norm > 0.0) {
    c /= norm;
    s /= norm;
  }
}

}  // namespace

// [SECTION] Geometry

Result<UrGeometry> ur_geometry(const RobotModel& model) {
  // Built only on failure: solve_ik_nearest asks on every call.
  const auto who = [&model] {
    return "robot '" + model.name() + "' is not of the UR class (closed-form IK): ";
  };
  if (model.dof() != 6) {
    return Error{who() + "it has " + std::to_string(model.dof()) + " joints, needs 6"};
  }
  UrGeometry g;
  // Every axis at q = 0 (offsets included), as a line in the base frame.
  Eigen::Isometry3d F = Eigen::Isometry3d::Identity();
  for (int i = 0; i < 6; ++i) {
    const Joint& joint = model.joint(i);
    if (joint.type != JointType::kRevolute) {
      return Error{who() + "joint " + std::to_string(i + 1) + " is prismatic, needs revolute"};
    }
    const Eigen::Isometry3d A = F * joint.before;
    g.axis[static_cast<size_t>(i)] = A.linear().col(2).normalized();
    g.point[static_cast<size_t>(i)] = A.translation();
    F = A * Eigen::AngleAxisd(joint.offset, Eigen::Vector3d::UnitZ()) * joint.after;
    g.lower[static_cast<size_t>(i)] = model.lower_limits()[i];
    g.upper[static_cast<size_t>(i)] = model.upper_limits()[i];
  }
  const Eigen::Isometry3d M = F * model.T_flange_tool();
  const auto& w = g.axis;
  const auto& p = g.point;
  g.n = w[1];
  for (int i : {2, 3}) {
    if (w[1].cross(w[static_cast<size_t>(i)]).norm() > kGeometryTolerance) {
      return Error{who() + "the axes of joints 2 and " + std::to_string(i + 1) +
                   " are not parallel (" +
                   format_angle(line_angle(w[1], w[static_cast<size_t>(i)])) + " apart)"};
    }
  }
  const auto perpendicular = [&](int a, int b) -> Status {
    const double cosine = w[static_cast<size_t>(a)].dot(w[static_cast<size_t>(b)]);
    if (std::abs(cosine) <= kGeometryTolerance) return Status::Ok();
    return Error{who() + "the axes of joints " + std::to_string(a + 1) + " and " +
                 std::to_string(b + 1) + " are not perpendicular (" +
                 format_angle(std::acos(std::clamp(cosine, -1.0, 1.0))) + " apart)"};
  };
  for (Status s : {perpendicular(0, 1), perpendicular(4, 1), perpendicular(4, 5)}) {
    if (!s) return s.error();
  }
  // Closest points of axes 5 and 6 (perpendicular, so never parallel).
  const Eigen::Vector3d d56 = p[5] - p[4];
  const double b = w[4].dot(w[5]);
  const double denominator = 1.0 - b * b;
  const double t5 = (w[4].dot(d56) - b * w[5].dot(d56)) / denominator;
  const double t6 = (b * w[4].dot(d56) - w[5].dot(d56)) / denominator;
  const Eigen::Vector3d on5 = p[4] + t5 * w[4];
  const Eigen::Vector3d on6 = p[5] + t6 * w[5];
  if ((on5 - on6).norm() > kGeometryTolerance) {
    return Error{who() + "the axes of joints 5 and 6 do not intersect (they pass " +
                 format_length((on5 - on6).norm()) + " apart)"};
  }
  g.wrist = 0.5 * (on5 + on6);
  const Eigen::Vector3d upper_arm = across(g.n, p[2] - p[1]);
  const Eigen::Vector3d forearm = across(g.n, p[3] - p[2]);
  g.upper_arm = upper_arm.norm();
  g.forearm = forearm.norm();
  if (g.upper_arm < kMinLinkLength) {
    return Error{who() + "the axes of joints 2 and 3 coincide (no upper arm)"};
  }
  if (g.forearm < kMinLinkLength) {
    return Error{who() + "the axes of joints 3 and 4 coincide (no forearm)"};
  }
  g.sign3 = w[2].dot(g.n) > 0.0 ? 1.0 : -1.0;
  g.sign4 = w[3].dot(g.n) > 0.0 ? 1.0 : -1.0;
  g.w1_cross_n = w[0].cross(g.n).normalized();
  g.shoulder_offset = g.n.dot(g.wrist - p[0]);
  g.R_M = M.linear();
  g.wrist_in_tool = M.inverse() * g.wrist;
  g.axis6_in_tool = g.R_M.transpose() * w[5];
  // n . Rot(w5, q5) w6 = (n . w6) cos q5 + (n . (w5 x w6)) sin q5 = cos(q5 - phi5).
  g.wrist_zero_angle = std::atan2(g.n.dot(w[4].cross(w[5])), g.n.dot(w[5]));
  g.elbow_zero_angle = angle_about(g.n, upper_arm, forearm);
  return g;
}

// [SECTION] Closed form

void solve_ur_ik(const UrGeometry& g, const Eigen::Isometry3d& T, UrIkSolutions& out,
                 const Vector6d& q_free) {
  out.reach = UrReach::kReachable;
  out.valid.fill(false);
  out.axis_distance = 0.0;
  out.nearest_reach = 0.0;
  if (!T.matrix().allFinite()) {
    out.reach = UrReach::kNotFinite;
    return;
  }
  const auto& w = g.axis;
  const auto& p = g.point;
  const Eigen::Vector3d& n = g.n;
  const Eigen::Matrix3d& R_T = T.linear();

  // Joint 1: n(q1) . (W - p1) = c, n(q1) = n cos q1 + (w1 x n) sin q1.
  const Eigen::Vector3d W = T * g.wrist_in_tool;
  const Eigen::Vector3d d = W - p[0];
  const double A = n.dot(d), B = g.w1_cross_n.dot(d);
  const double c = g.shoulder_offset;
  const double r = std::sqrt(A * A + B * B);
  out.axis_distance = r;
  if (r < std::abs(c) - kReachTolerance) {
    out.reach = UrReach::kInsideCylinder;
    return;
  }
  // x: the wrist point's distance from the plane through axis 1 parallel to n(q1).
  const double x = std::sqrt(std::max(0.0, r * r - c * c));
  const bool shoulder_singular = x < kSingularTolerance;
  std::array<double, 2> q1;  // [0] 'l', [1] 'r'
  if (r > kDegenerate) {
    const double phi = std::atan2(B, A);
    const double alpha = std::atan2(x, c);  // acos(c / r)
    q1 = {phi + alpha, phi - alpha};
  } else {
    q1 = {q_free[0], q_free[0]};  // wrist point on axis 1 (c = 0): q1 is free
  }

  const Eigen::Vector3d z6 = R_T * g.axis6_in_tool;  // axis 6 in the base frame
  // T M^-1: carries points of the q = 0 arm (beyond joint 6) to where the target puts them.
  const Eigen::Matrix3d R_TM = R_T * g.R_M.transpose();
  // T M^-1 x = R_TM x + t_TM, and T M^-1 W0 = W.
  const Eigen::Vector3d t_TM = W - R_TM * g.wrist;
  const double l2 = g.upper_arm, l3 = g.forearm;
  const double max_reach = l2 + l3, min_reach = std::abs(l2 - l3);
  double nearest_miss = std::numeric_limits<double>::infinity();
  bool any_too_far = false, any_too_close = false;

  for (int lr = 0; lr < 2; ++lr) {
    const double a1 = q1[static_cast<size_t>(lr)];
    const double c1 = std::cos(a1), s1 = std::sin(a1);
    const Eigen::Vector3d n1 = rotate(w[0], c1, s1, n);  // n(q1)
    // Joint 5: n(q1) . z6 = cos(q5 - phi5).
    const double cos_beta = n1.dot(z6);
    const double sin_beta = n1.cross(z6).norm();
    const double beta = std::atan2(sin_beta, cos_beta);
    const bool wrist_singular = sin_beta < kSingularTolerance;
    // v = R'^T n with R' = Rot(w1, q1)^T R_TM: what joint 6 must turn onto Rot(w5, -q5) n.
    const Eigen::Vector3d v = R_TM.transpose() * n1;
    for (int nf = 0; nf < 2; ++nf) {
      const double q5 = g.wrist_zero_angle + (nf == 0 ? beta : -beta);
      const double c5 = std::cos(q5), s5 = std::sin(q5);
      const Eigen::Vector3d u = rotate(w[4], c5, -s5, n);
      // The point of axis 4 that joints 6, 5 and 1 carried back leave for a given q6: only
      // joints 2 and 3 move it. Across n, from the shoulder axis: the planar problem's target.
      const auto axis4_target = [&](double c6, double s6) {
        const Eigen::Vector3d arm4 = rotate(w[5], c6, -s6, rotate(w[4], c5, -s5, p[3] - g.wrist));
        const Eigen::Vector3d world4 = R_TM * (g.wrist + arm4) + t_TM;
        const Eigen::Vector3d t4 = p[0] + rotate(w[0], c1, -s1, world4 - p[0]);
        return Eigen::Vector3d(across(n, t4 - p[1]));
      };
      const auto out_of_reach = [&](double d) {
        return d > max_reach + kReachTolerance || d < min_reach - kReachTolerance;
      };
      double q6;
      const bool q6_free = !(sin_beta > kDegenerate);
      if (!q6_free) {
        // The projections themselves, not v.u - (w6.v)(w6.u): near the wrist singularity
        // they are of length sin(beta), and that difference would cancel to rounding noise.
        const Eigen::Vector3d v_across = across(w[5], v), u_across = across(w[5], u);
        q6 = angle_about(w[5], v_across, u_across);
      } else {
        q6 = q_free[5];  // axis 6 parallel to n: only q6 + s theta is determined
      }
      Eigen::Vector3d delta = axis4_target(std::cos(q6), std::sin(q6));
      double D = delta.norm();
      if (q6_free && out_of_reach(D)) {
        // Axis 6 is parallel to n, so q6 moves that point on a circle across n:
        // delta(q6) = centre + Rot(n, s q6) spoke. Of the q6 that bring it within reach, the
        // one nearest q_free (a q6 chosen freely must not lose the branch).
        const Eigen::Vector3d at_0 = axis4_target(1.0, 0.0), at_pi = axis4_target(-1.0, 0.0);
        const Eigen::Vector3d centre = 0.5 * (at_0 + at_pi), spoke = 0.5 * (at_0 - at_pi);
        const double turn = n.dot(spoke.cross(axis4_target(0.0, 1.0) - centre)) >= 0.0 ? 1.0 : -1.0;
        const double C = centre.norm(), rho = spoke.norm();
        const double wanted = std::clamp(D, min_reach, max_reach);
        if (C > kDegenerate && rho > kDegenerate) {
          // wanted^2 = C^2 + rho^2 + 2 C rho cos(gamma), gamma the angle from the centre's
          // direction to the turned spoke, phi0 + turn q6.
          const double cos_gamma = (wanted * wanted - C * C - rho * rho) / (2.0 * C * rho);
          if (std::abs(cos_gamma) <= 1.0 + kDegenerate) {
            const double gamma = std::acos(std::clamp(cos_gamma, -1.0, 1.0));
            const double phi0 = angle_about(n, centre, spoke);
            const double a = wrap_small_angle(turn * (gamma - phi0));
            const double b = wrap_small_angle(turn * (-gamma - phi0));
            q6 = std::abs(wrap_small_angle(a - q_free[5])) <=
                         std::abs(wrap_small_angle(b - q_free[5]))
                     ? a
                     : b;
            delta = axis4_target(std::cos(q6), std::sin(q6));
            D = delta.norm();
          }
        }
      }
      if (out_of_reach(D)) {
        const double miss = D > max_reach ? D - max_reach : min_reach - D;
        if (miss < nearest_miss) {
          nearest_miss = miss;
          out.nearest_reach = D;
        }
        (D > max_reach ? any_too_far : any_too_close) = true;
        continue;
      }
      const double c6 = std::cos(q6), s6 = std::sin(q6);
      // theta: Rot(n, theta) = R' Rot(w6, -q6) Rot(w5, -q5), read off its action on w5.
      // (Rot(w5, -q5) leaves w5 as it is.)
      const Eigen::Vector3d w5_turned = rotate(w[0], c1, -s1, R_TM * rotate(w[5], c6, -s6, w[4]));
      const double theta = angle_about(n, w[4], w5_turned);
      double cos_psi, sin_psi;
      elbow_angle(l2, l3, std::clamp(D, min_reach, max_reach), cos_psi, sin_psi);
      const double psi = std::atan2(sin_psi, cos_psi);  // >= 0
      const bool elbow_singular = l2 * l3 * sin_psi < kSingularTolerance * std::max(D, l2);
      const Eigen::Vector3d upper = across(n, p[2] - p[1]);
      const Eigen::Vector3d fore = across(n, p[3] - p[2]);
      // The two elbows: psi and -psi. 'u' is the one whose elbow axis lies on the +w1 side
      // of the line from the shoulder axis to the wrist-1 axis (mirror images across it).
      std::array<double, 2> q2_of, q3_of;  // [0] +psi, [1] -psi
      double lift = 0.0;                   // +psi's elbow: its w1 component off the line
      for (int k = 0; k < 2; ++k) {
        const double turn3 = (k == 0 ? psi : -psi) - g.elbow_zero_angle;  // s3 q3
        const Eigen::Vector3d reach = upper + rotate(n, turn3, fore);
        const double q2 = D > kDegenerate ? angle_about(n, reach, delta) : q_free[1];
        q2_of[static_cast<size_t>(k)] = q2;
        q3_of[static_cast<size_t>(k)] = g.sign3 * turn3;
        if (k == 0 && D > kDegenerate) {
          const Eigen::Vector3d elbow = rotate(n, q2, upper);
          const Eigen::Vector3d line = delta / D;
          lift = w[0].dot(elbow - line.dot(elbow) * line);
        }
      }
      const int up = lift >= 0.0 ? 0 : 1;  // which of [+psi, -psi] is 'u'
      for (int ud = 0; ud < 2; ++ud) {
        const int k = ud == 0 ? up : 1 - up;
        const int index = lr * 4 + ud * 2 + nf;
        const double q2 = q2_of[static_cast<size_t>(k)];
        const double q3 = q3_of[static_cast<size_t>(k)];
        const double q4 = g.sign4 * (theta - q2 - g.sign3 * q3);
        Vector6d& q = out.q[static_cast<size_t>(index)];
        q << a1, q2, q3, q4, q5, q6;
        bool inside = true;
        for (int j = 0; j < 6; ++j) {
          q[j] = wrap_small_angle(q[j]);
          inside =
              inside && angle_equivalent_within(q[j], g.lower[static_cast<size_t>(j)],
                                                g.upper[static_cast<size_t>(j)], kLimitTolerance);
        }
        out.valid[static_cast<size_t>(index)] = true;
        out.within_limits[static_cast<size_t>(index)] = inside;
        unsigned bits = 0;
        if (wrist_singular) bits |= static_cast<unsigned>(PumaSingularity::kWrist);
        if (elbow_singular) bits |= static_cast<unsigned>(PumaSingularity::kElbow);
        if (shoulder_singular) bits |= static_cast<unsigned>(PumaSingularity::kShoulder);
        out.singularity[static_cast<size_t>(index)] = bits;
      }
    }
  }
  if (std::none_of(out.valid.begin(), out.valid.end(), [](bool b) { return b; })) {
    out.reach = any_too_far && !any_too_close ? UrReach::kTooFar : UrReach::kTooClose;
  }
}

// [SECTION] Labelled API

namespace {

std::string ur_unreachable_message(const UrGeometry& g, const UrIkSolutions& s) {
  const double max_reach = g.upper_arm + g.forearm;
  const double min_reach = std::abs(g.upper_arm - g.forearm);
  switch (s.reach) {
    case UrReach::kNotFinite:
      return "target pose is not finite";
    case UrReach::kInsideCylinder:
      return "target unreachable: the wrist point is " + format_length(s.axis_distance) +
             " from joint 1's axis, inside the shoulder-offset cylinder of radius " +
             format_length(std::abs(g.shoulder_offset));
    case UrReach::kTooFar:
      return "target unreachable: in every branch the wrist-1 axis would be beyond the arm's "
             "reach of " +
             format_length(max_reach) +
             " from the shoulder axis (nearest: " + format_length(s.nearest_reach) + ")";
    case UrReach::kTooClose:
      return "target unreachable: in no branch does the wrist-1 axis fall within the arm's "
             "reach of " +
             format_length(min_reach) + " .. " + format_length(max_reach) +
             " from the shoulder axis (nearest: " + format_length(s.nearest_reach) + ")";
    case UrReach::kReachable:
      break;
  }
  return {};
}

// Newton steps on FK(q) = T where the closed form left more than kPolishTolerance (near a
// singularity, where its rounding is amplified); a step is kept only when it reduces the
// error.
void polish(const RobotModel& model, KinematicsData& data, const Eigen::Isometry3d& T,
            Eigen::VectorXd& q) {
  const auto error_of = [&](const Eigen::VectorXd& x, Vector6d& e) {
    forward_kinematics(model, data, x);
    e = pose_error_in_base(data.T_base_tool, T);
    return std::max(e.head<3>().norm(), e.tail<3>().norm());
  };
  // The usual case first, without the rotation's logarithm: every entry within the tolerance
  // (rotation entries differ by about the angle of the rotation between them).
  forward_kinematics(model, data, q);
  if ((data.T_base_tool.matrix() - T.matrix()).cwiseAbs().maxCoeff() <= 0.5 * kPolishTolerance) {
    return;
  }
  Vector6d e;
  double err = error_of(q, e);
  Jacobian J(6, 6);
  for (int step = 0; step < kPolishSteps && err > kPolishTolerance; ++step) {
    forward_kinematics(model, data, q);
    geometric_jacobian(model, data, JacobianFrame::kBase, J);
    // Newton's step, undamped: next to a singularity the joints must move by error / sigma
    // along the weak direction. A step that does not help is not taken.
    const Eigen::Matrix<double, 6, 6> Jf = J;
    const Vector6d dq = Jf.partialPivLu().solve(e);
    if (!dq.allFinite()) break;
    const Eigen::VectorXd trial = q + dq;
    Vector6d e_trial;
    const double err_trial = error_of(trial, e_trial);
    if (!(err_trial < err)) break;
    q = trial;
    e = e_trial;
    err = err_trial;
  }
}

}  // namespace

AnalyticIkResult solve_ur_analytic_ik(const RobotModel& model, const UrGeometry& geometry,
                                      const Eigen::Isometry3d& T_base_tool, std::string_view config,
                                      const Vector6d& q_free) {
  assert(model.dof() == 6 && "solve_ur_analytic_ik(): the model is not a 6-joint arm");
  AnalyticIkResult result;
  if (Status s = check_ik_config(config); !s) {
    assert(false && "solve_ur_analytic_ik(): invalid configuration string (check_ik_config)");
    result.status = IkStatus::kUnreachable;
    result.message = s.error().message;
    return result;
  }
  UrIkSolutions raw;
  solve_ur_ik(geometry, T_base_tool, raw, q_free);
  if (!raw.reachable()) {
    result.status = IkStatus::kUnreachable;
    result.message = ur_unreachable_message(geometry, raw);
    return result;
  }
  KinematicsData data(model);
  unsigned singular_bits = 0;
  for (int i = 0; i < UrIkSolutions::kCount; ++i) {
    const auto k = static_cast<size_t>(i);
    const char* label = UrIkSolutions::kConfigs[k];
    if (!raw.valid[k] || !ik_config_matches(label, config)) continue;
    IkSolution& s = result.solutions.emplace_back();
    s.config = label;
    s.q = raw.q[k];
    s.within_limits = raw.within_limits[k];
    polish(model, data, T_base_tool, s.q);
    if (s.q != Eigen::VectorXd(raw.q[k])) {
      s.within_limits = true;
      for (int j = 0; j < 6; ++j) {
        s.q[j] = wrap_small_angle(s.q[j]);
        s.within_limits =
            s.within_limits &&
            angle_equivalent_within(s.q[j], geometry.lower[static_cast<size_t>(j)],
                                    geometry.upper[static_cast<size_t>(j)], kLimitTolerance);
      }
    }
    s.singular = raw.singularity[k] != 0;
    singular_bits |= raw.singularity[k];
  }
  if (result.solutions.empty()) {
    result.status = IkStatus::kUnreachable;
    result.message = "target unreachable in configuration '" + std::string(config) +
                     "' (other branches reach it)";
    return result;
  }
  if (singular_bits != 0) {
    result.status = IkStatus::kSingular;
    result.message = singularity_message(
        singular_bits,
        "wrist singularity (axis 6 parallel to axes 2-4: only q6 and q2 + q3 + q4 together "
        "are determined)",
        "elbow singularity (arm fully stretched or folded: 'u' and 'd' coincide)",
        "shoulder singularity (wrist point in the plane of joint 1's axis and the shoulder "
        "axis: 'l' and 'r' coincide)");
  }
  return result;
}

}  // namespace telear::core
