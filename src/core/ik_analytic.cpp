#include "telear/core/ik_analytic.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "telear/core/angles.hpp"
#include "telear/core/joint_limits.hpp"
#include "telear/core/number_format.hpp"

#include "ik_common.hpp"

namespace telear::core {
namespace {

// Below this, the ZYZ decomposition's first angle is undetermined (the Toolbox's 10 eps).
constexpr double kEulerDegenerate = 10.0 * std::numeric_limits<double>::epsilon();
constexpr double kDhTolerance = 1e-9;  // rad or m, for the class checks

// Unit complex numbers (cos, sin) for exact angle sums without trigonometric calls. Lengths
// here are of order 1 (unit vectors, metres), so sqrt(x^2 + y^2) cannot overflow and is several
// times faster than std::hypot.
struct Rot2 {
  double c = 1.0;
  double s = 0.0;
};
inline Rot2 operator*(Rot2 a, Rot2 b) {
  return {a.c * b.c - a.s * b.s, a.s * b.c + a.c * b.s};
}
inline Rot2 normalized_rot2(double c, double s) {
  const double n = std::sqrt(c * c + s * s);
  return n > 0.0 ? Rot2{c / n, s / n} : Rot2{};
}

// Sine and cosine of the angle between sides `a` and `c` of the triangle (a, b, c), accurate
// for needle-like triangles (Kahan's area formula) where acos of the cosine rule is not.
Rot2 triangle_angle(double a, double b, double c) {
  const double cosine = (a * a + c * c - b * b) / (2.0 * a * c);
  double x = a, y = b, z = c;  // sort x >= y >= z
  if (x < y) std::swap(x, y);
  if (y < z) std::swap(y, z);
  if (x < y) std::swap(x, y);
  const double product = (x + (y + z)) * (z - (x - y)) * (z + (x - y)) * (x + (y - z));
  const double area = 0.25 * std::sqrt(std::max(0.0, product));
  return normalized_rot2(cosine, 2.0 * area / (a * c));
}

}  // namespace

// [SECTION] Geometry

Result<PumaGeometry> puma_geometry(const RobotModel& model) {
  const std::string who =
      "robot '" + model.name() + "' is not of the PUMA class (closed-form IK): ";
  if (!model.dh()) {
    return Error{"robot '" + model.name() +
                 "' has no standard DH table (the PUMA class's closed form reads one; a URDF arm "
                 "has the UR class's, ik_ur.hpp, or numeric IK)"};
  }
  if (model.dof() != 6) {
    return Error{who + "it has " + std::to_string(model.dof()) + " joints, needs 6"};
  }
  const std::vector<DhRow>& dh = *model.dh();
  for (int i = 0; i < 6; ++i) {
    if (model.joint(i).type != JointType::kRevolute) {
      return Error{who + "joint " + std::to_string(i + 1) + " is prismatic, needs revolute"};
    }
  }
  const double h = std::numbers::pi / 2.0;
  const std::array<double, 5> pattern = {h, 0.0, -h, h, -h};
  const bool mirrored = std::abs(dh[0].alpha + h) < kDhTolerance;
  const double sign = mirrored ? -1.0 : 1.0;
  for (int i = 0; i < 5; ++i) {
    const double expected = sign * pattern[static_cast<size_t>(i)];
    if (std::abs(dh[static_cast<size_t>(i)].alpha - expected) > kDhTolerance) {
      return Error{who + "joint " + std::to_string(i + 1) +
                   " has alpha = " + format_angle(dh[static_cast<size_t>(i)].alpha) + ", needs " +
                   format_angle(expected) + " (alpha pattern +90, 0, -90, +90, -90 deg" +
                   (mirrored ? ", mirrored as joint 1 has -90 deg)" : ", or all negated)")};
    }
  }
  const auto require_zero = [&](double value, int joint, const char* name) -> Status {
    if (std::abs(value) > kDhTolerance) {
      return Error{who + "joint " + std::to_string(joint) + " has " + name + " = " +
                   format_length(value) + ", needs 0"};
    }
    return Status::Ok();
  };
  for (Status s : {require_zero(dh[0].a, 1, "a"), require_zero(dh[3].a, 4, "a"),
                   require_zero(dh[4].a, 5, "a"), require_zero(dh[4].d, 5, "d")}) {
    if (!s) return s.error();
  }
  if (std::abs(dh[1].a) <= kDhTolerance) {
    return Error{who + "joint 2 has a = 0 (no upper arm), needs a non-zero a2"};
  }
  if (std::hypot(dh[2].a, dh[3].d) <= kDhTolerance) {
    return Error{who + "a3 and d4 are both 0 (no forearm)"};
  }
  PumaGeometry g;
  g.mirrored = mirrored;
  // The mirrored chain is N A(-theta; -d, -a, alpha) N with N = Ry(pi): solve the image.
  g.d1 = sign * dh[0].d;
  g.a2 = sign * dh[1].a;
  g.a3 = sign * dh[2].a;
  g.d4 = sign * dh[3].d;
  g.shoulder_offset = sign * (dh[1].d + dh[2].d);
  for (size_t i = 0; i < 6; ++i) {
    g.offset[i] = dh[i].offset;
    g.lower[i] = model.lower_limits()[static_cast<Eigen::Index>(i)];
    g.upper[i] = model.upper_limits()[static_cast<Eigen::Index>(i)];
  }
  const DhRow& last = dh[5];
  g.T_wrist_tool = Eigen::Translation3d(last.a, 0.0, last.d) *
                   Eigen::AngleAxisd(last.alpha, Eigen::Vector3d::UnitX()) * model.T_flange_tool();
  g.T_tool_wrist = g.T_wrist_tool.inverse();
  g.forearm = std::hypot(g.a3, g.d4);
  g.forearm_angle = std::atan2(g.d4, g.a3);
  g.min_reach = std::abs(std::abs(g.a2) - g.forearm);
  g.max_reach = std::abs(g.a2) + g.forearm;
  return g;
}

// [SECTION] Closed form

void solve_puma_ik(const PumaGeometry& g, const Eigen::Isometry3d& T_base_tool,
                   PumaIkSolutions& out) {
  out.reach = PumaReach::kReachable;
  out.wrist_distance = 0.0;
  out.axis_distance = 0.0;
  if (!T_base_tool.matrix().allFinite()) {
    out.reach = PumaReach::kNotFinite;
    return;
  }
  // W = T_0_5 Rz(theta6): its origin is the wrist centre.
  const Eigen::Isometry3d W = T_base_tool * g.T_tool_wrist;
  Eigen::Matrix3d R = W.linear();
  Eigen::Vector3d p = W.translation();
  if (g.mirrored) {  // N W N with N = diag(-1, 1, -1)
    R(0, 1) = -R(0, 1);
    R(1, 0) = -R(1, 0);
    R(1, 2) = -R(1, 2);
    R(2, 1) = -R(2, 1);
    p.x() = -p.x();
    p.z() = -p.z();
  }
  const double px = p.x(), py = p.y(), pz = p.z() - g.d1;
  const double D = g.shoulder_offset;

  // Joint 1: px sin(theta1) - py cos(theta1) = D.
  const double r2 = px * px + py * py;
  const double r = std::sqrt(r2);
  out.axis_distance = r;
  if (r < std::abs(D) - kReachTolerance) {
    out.reach = PumaReach::kInsideCylinder;
    return;
  }
  const double x1 = std::sqrt(std::max(0.0, r2 - D * D));  // V114 of 'r'; 'l' has -x1
  const double phi = std::atan2(py, px);
  const double alpha = std::atan2(D, x1);  // asin(D / r)
  std::array<Rot2, 2> rot1;                // [0] 'l', [1] 'r'
  std::array<double, 2> theta1;
  theta1[1] = phi + alpha;
  theta1[0] = phi + std::numbers::pi - alpha;
  if (r2 > 0.0) {
    rot1[1] = {(px * x1 - py * D) / r2, (py * x1 + px * D) / r2};
    rot1[0] = {-(px * x1 + py * D) / r2, -(py * x1 - px * D) / r2};
  } else {
    rot1[1] = {1.0, 0.0};
    rot1[0] = {-1.0, 0.0};
  }
  const bool shoulder_singular = x1 < kSingularTolerance;

  // Joints 2 and 3: planar two-link arm (a2, forearm) reaching (+-x1, pz).
  const double rho = std::sqrt(x1 * x1 + pz * pz);
  out.wrist_distance = rho;
  if (rho > g.max_reach + kReachTolerance) {
    out.reach = PumaReach::kTooFar;
    return;
  }
  if (rho < g.min_reach - kReachTolerance) {
    out.reach = PumaReach::kTooClose;
    return;
  }
  const double A = std::abs(g.a2);
  const double B = g.forearm;
  // Psi: angle at the shoulder between the wrist direction and the upper arm.
  Rot2 psi{1.0, 0.0};
  if (rho > 0.0) {
    const double rho_c = std::clamp(rho, g.min_reach, g.max_reach);
    psi = triangle_angle(A, B, rho_c);
  }
  const bool elbow_singular = psi.s * rho < kSingularTolerance * B;
  const Rot2 beta{g.a3 / B, g.d4 / B};  // forearm_angle = atan2(d4, a3)
  const Rot2 beta_inv{beta.c, -beta.s};
  const double shift_a2 = g.a2 < 0.0 ? std::numbers::pi : 0.0;
  const double psi_angle = std::atan2(psi.s, psi.c);
  // Elbow angle epsilon = theta3 + beta (- pi when a2 < 0) for n2 = +1; n2 = -1 negates it.
  const Rot2 eps_up = normalized_rot2(rho * psi.c - A, -rho * psi.s);
  const double eps_up_angle = std::atan2(eps_up.s, eps_up.c);

  // gamma = atan2(Pz, V114): 'r' has V114 = x1, 'l' has -x1, i.e. pi - gamma_r (mod 2 pi).
  const double gamma_r = rho > 0.0 ? std::atan2(pz, x1) : 0.0;
  const std::array<double, 2> gamma_angles = {rho > 0.0 ? std::numbers::pi - gamma_r : 0.0,
                                              gamma_r};
  for (int lr = 0; lr < 2; ++lr) {  // 0 'l', 1 'r'
    const double xw = lr == 1 ? x1 : -x1;
    const Rot2 gamma = rho > 0.0 ? Rot2{xw / rho, pz / rho} : Rot2{};
    const double gamma_angle = gamma_angles[static_cast<size_t>(lr)];
    const Rot2 c1 = rot1[static_cast<size_t>(lr)];
    // M = Rz(-theta1) R: rows mixed by theta1.
    Eigen::Matrix3d M;
    M.row(0) = c1.c * R.row(0) + c1.s * R.row(1);
    M.row(1) = -c1.s * R.row(0) + c1.c * R.row(1);
    M.row(2) = R.row(2);
    for (int ud = 0; ud < 2; ++ud) {  // 0 'u', 1 'd'
      double n2 = ud == 0 ? 1.0 : -1.0;
      if (lr == 0) n2 = -n2;
      const Rot2 psi_n{psi.c, n2 * psi.s};
      const Rot2 eps{eps_up.c, n2 * eps_up.s};
      const double theta2 = gamma_angle + n2 * psi_angle + shift_a2;
      const double theta3 = n2 * eps_up_angle + shift_a2 - g.forearm_angle;
      // theta2 + theta3 = gamma + n2 psi + eps - beta (+ 2 pi when a2 < 0).
      const Rot2 c23 = gamma * psi_n * eps * beta_inv;
      // R_3_6 = Ry(theta23) M = Rz(theta4) Ry(-theta5) Rz(theta6).
      Eigen::Matrix3d E;
      E.row(0) = c23.c * M.row(0) + c23.s * M.row(2);
      E.row(1) = M.row(1);
      E.row(2) = -c23.s * M.row(0) + c23.c * M.row(2);
      const double s5 = std::sqrt(E(0, 2) * E(0, 2) + E(1, 2) * E(1, 2));
      double e_phi, e_theta, e_psi;
      const bool degenerate =
          std::abs(E(0, 2)) < kEulerDegenerate && std::abs(E(1, 2)) < kEulerDegenerate;
      if (degenerate) {
        // Only theta4 +- theta6 is determined: theta4 = 0 as the Toolbox does.
        e_phi = 0.0;
        e_theta = std::atan2(E(0, 2), E(2, 2));
        e_psi = std::atan2(E(1, 0), E(1, 1));
      } else {
        const double cp = E(0, 2) / s5, sp = E(1, 2) / s5;
        e_phi = std::atan2(E(1, 2), E(0, 2));
        e_theta = std::atan2(s5, E(2, 2));
        e_psi = std::atan2(-sp * E(0, 0) + cp * E(1, 0), -sp * E(0, 1) + cp * E(1, 1));
      }
      const bool wrist_singular = s5 < kSingularTolerance;
      for (int nf = 0; nf < 2; ++nf) {  // 0 'n', 1 'f'
        const int index = lr * 4 + ud * 2 + nf;
        const bool flip = nf == 1 && !degenerate;  // degenerate: 'n' and 'f' coincide
        double theta[6] = {theta1[static_cast<size_t>(lr)],
                           theta2,
                           theta3,
                           flip ? e_phi + std::numbers::pi : e_phi,
                           flip ? e_theta : -e_theta,  // theta5 = -th since alpha4 > 0
                           flip ? e_psi + std::numbers::pi : e_psi};
        Vector6d& q = out.q[static_cast<size_t>(index)];
        bool inside = true;
        for (int j = 0; j < 6; ++j) {
          const double t = g.mirrored ? -theta[j] : theta[j];
          q[j] = wrap_small_angle(t - g.offset[static_cast<size_t>(j)]);
          inside =
              inside && angle_equivalent_within(q[j], g.lower[static_cast<size_t>(j)],
                                                g.upper[static_cast<size_t>(j)], kLimitTolerance);
        }
        out.within_limits[static_cast<size_t>(index)] = inside;
        unsigned bits = 0;
        if (wrist_singular) bits |= static_cast<unsigned>(PumaSingularity::kWrist);
        if (elbow_singular) bits |= static_cast<unsigned>(PumaSingularity::kElbow);
        if (shoulder_singular) bits |= static_cast<unsigned>(PumaSingularity::kShoulder);
        out.singularity[static_cast<size_t>(index)] = bits;
      }
    }
  }
}

// [SECTION] Public API

Status check_ik_config(std::string_view config) {
  bool seen[3] = {false, false, false};
  for (char c : config) {
    int pair = -1;
    if (c == 'l' || c == 'r') pair = 0;
    if (c == 'u' || c == 'd') pair = 1;
    if (c == 'n' || c == 'f') pair = 2;
    if (pair < 0) {
      return Error{"configuration '" + std::string(config) + "': unknown letter '" +
                   std::string(1, c) + "' (use l/r, u/d, n/f, e.g. \"lun\")"};
    }
    if (seen[pair]) {
      return Error{"configuration '" + std::string(config) + "': more than one of l/r, u/d or n/f"};
    }
    seen[pair] = true;
  }
  return Status::Ok();
}

bool ik_config_matches(std::string_view label, std::string_view config) {
  for (char c : config) {
    if (label.find(c) == std::string_view::npos) return false;
  }
  return true;
}

namespace {

std::string puma_unreachable_message(const PumaGeometry& g, const PumaIkSolutions& s) {
  switch (s.reach) {
    case PumaReach::kNotFinite:
      return "target pose is not finite";
    case PumaReach::kInsideCylinder:
      return "target unreachable: the wrist centre is " + format_length(s.axis_distance) +
             " from joint 1's axis, inside the shoulder-offset cylinder of radius " +
             format_length(std::abs(g.shoulder_offset));
    case PumaReach::kTooFar:
      return "target unreachable: the wrist centre is " + format_length(s.wrist_distance) +
             " from the shoulder, beyond the arm's reach of " + format_length(g.max_reach);
    case PumaReach::kTooClose:
      return "target unreachable: the wrist centre is " + format_length(s.wrist_distance) +
             " from the shoulder, closer than the arm's minimum reach of " +
             format_length(g.min_reach);
    case PumaReach::kReachable:
      break;
  }
  return {};
}

}  // namespace

std::string singularity_message(unsigned bits, std::string_view wrist, std::string_view elbow,
                                std::string_view shoulder) {
  std::string m;
  const auto add = [&m](std::string_view text) {
    if (!m.empty()) m += "; ";
    m += text;
  };
  if (bits & static_cast<unsigned>(PumaSingularity::kWrist)) add(wrist);
  if (bits & static_cast<unsigned>(PumaSingularity::kElbow)) add(elbow);
  if (bits & static_cast<unsigned>(PumaSingularity::kShoulder)) add(shoulder);
  return m;
}

AnalyticIkResult solve_analytic_ik(const RobotModel& model, const PumaGeometry& geometry,
                                   const Eigen::Isometry3d& T_base_tool, std::string_view config) {
  assert(model.dof() == 6 && "solve_analytic_ik(): the model is not a 6-joint arm");
  (void)model;
  AnalyticIkResult result;
  if (Status s = check_ik_config(config); !s) {
    assert(false && "solve_analytic_ik(): invalid configuration string (use check_ik_config)");
    result.status = IkStatus::kUnreachable;
    result.message = s.error().message;
    return result;
  }
  PumaIkSolutions raw;
  solve_puma_ik(geometry, T_base_tool, raw);
  if (!raw.reachable()) {
    result.status = IkStatus::kUnreachable;
    result.message = puma_unreachable_message(geometry, raw);
    return result;
  }
  result.solutions.reserve(PumaIkSolutions::kCount);
  unsigned singular_bits = 0;
  for (int i = 0; i < PumaIkSolutions::kCount; ++i) {
    const char* label = PumaIkSolutions::kConfigs[static_cast<size_t>(i)];
    if (!ik_config_matches(label, config)) continue;
    IkSolution& s = result.solutions.emplace_back();
    s.config = label;
    s.q = raw.q[static_cast<size_t>(i)];
    s.within_limits = raw.within_limits[static_cast<size_t>(i)];
    s.singular = raw.singularity[static_cast<size_t>(i)] != 0;
    singular_bits |= raw.singularity[static_cast<size_t>(i)];
  }
  if (singular_bits != 0) {
    result.status = IkStatus::kSingular;
    result.message = singularity_message(
        singular_bits,
        "wrist singularity (q5 ~ 0: joints 4 and 6 aligned, only q4 + q6 is determined)",
        "elbow singularity (arm fully stretched or folded: 'u' and 'd' coincide)",
        "shoulder singularity (wrist centre on the shoulder-offset cylinder: 'l' and 'r' "
        "coincide)");
  }
  return result;
}

}  // namespace telear::core
