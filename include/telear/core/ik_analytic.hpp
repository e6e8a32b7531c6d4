#pragma once
// Closed-form inverse kinematics of the PUMA 560 and of every arm of its geometry class
// (Paul & Zhang, "Computationally efficient kinematics for manipulators with spherical
// wrists", IJRR 5(2) 1986), with the Robotics Toolbox's configuration letters.
//
// The class: six revolute joints, standard DH (T_i = Rz(theta_i) Tz(d_i) Tx(a_i) Rx(alpha_i),
// theta_i = q_i + offset_i) with
//
//   alpha = (+pi/2, 0, -pi/2, +pi/2, -pi/2, alpha6)   a1 = a4 = a5 = 0,  d5 = 0
//
// and arbitrary d1, a2 != 0, shoulder offset D = d2 + d3, a3, d4 (a3^2 + d4^2 > 0), d6, a6,
// alpha6, offsets and tool transform. The mirrored pattern (every alpha1..5 negated) is
// accepted too: conjugating by N = Ry(pi) maps it onto the pattern above with d, a and theta
// negated, and the letters are those of that image.
//
// Solution, with W = T_base_tool * (Tz(d6) Tx(a6) Rx(alpha6) T_flange_tool)^-1 = T_0_5 Rz(th6)
// whose origin p is the wrist centre:
//   theta1 = atan2(py, px) + asin(D / r)           'r'     r = hypot(px, py) >= |D|
//          = atan2(py, px) + pi - asin(D / r)      'l'
//   V114 = px cos theta1 + py sin theta1,  Pz = pz - d1,  rho = hypot(V114, Pz)
//   theta2 = atan2(Pz, V114) + n2 Psi,  Psi = acos((a2^2 - a3^2 - d4^2 + rho^2) / (2 a2 rho))
//            n2 = +1 for 'u', -1 for 'd', negated for 'l'
//   theta3 from the planar triangle (a2, hypot(a3, d4), rho)
//   R_3_6 = R_0_3^T R_W = Rz(theta4) Ry(-theta5) Rz(theta6): ZYZ Euler angles (phi, th, psi)
//   of R_3_6, 'n' without flip (th >= 0), 'f' with flip (th <= 0); theta5 = -th since
//   alpha4 > 0.
// exactly as the Robotics Toolbox's Puma560.ikine_a / DHRobot.ikine_6s. Joint values are
// wrapped to (-pi, pi]; `within_limits` also accepts a value whose 2*pi equivalent lies within
// the limits (solve_ik_nearest in inverse_kinematics.hpp does that shift).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "telear/core/pose.hpp"
#include "telear/core/result.hpp"
#include "telear/core/robot_model.hpp"

namespace telear::core {

// The numbers the closed form needs, extracted once from a model (cheap to copy).
struct PumaGeometry {
  double d1 = 0.0;                         // m, base to shoulder height
  double a2 = 0.0;                         // m, upper arm
  double a3 = 0.0;                         // m, elbow offset along the forearm's normal
  double d4 = 0.0;                         // m, forearm (elbow to wrist centre)
  double shoulder_offset = 0.0;            // m, d2 + d3
  bool mirrored = false;                   // alphas negated: d, a and theta above are the N-image's
  std::array<double, 6> offset{};          // rad, DH offsets (of the model, not the image)
  std::array<double, 6> lower{}, upper{};  // rad, joint limits
  // Fixed transform from frame "5 rotated by theta6" to the tool: Tz(d6) Tx(a6) Rx(alpha6)
  // T_flange_tool, and its inverse.
  Eigen::Isometry3d T_wrist_tool = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d T_tool_wrist = Eigen::Isometry3d::Identity();
  // Derived: forearm length hypot(a3, d4), its angle atan2(d4, a3), and the reach interval
  // of the wrist centre from the shoulder in the arm's plane.
  double forearm = 0.0;
  double forearm_angle = 0.0;
  double min_reach = 0.0;
  double max_reach = 0.0;
};

// The PUMA geometry of `model`, or an error that names the DH parameter breaking the class
// (needs model.dh(): URDF-loaded arms use numeric IK).
Result<PumaGeometry> puma_geometry(const RobotModel& model);

enum class IkStatus { kOk, kUnreachable, kSingular };

struct IkSolution {
  std::string config;  // "lun" ... "rdf", or "numeric"
  Eigen::VectorXd q;   // rad
  bool within_limits = false;
  bool singular = false;
};

struct AnalyticIkResult {
  IkStatus status = IkStatus::kOk;
  std::string message;  // why unreachable / which singularity; empty when kOk
  std::vector<IkSolution> solutions;
};

// Checks an untrusted configuration string: letters from {l,r}, {u,d}, {n,f}, at most one of
// each pair, e.g. "lun", "l", "un", "" (all).
Status check_ik_config(std::string_view config);

// true when the solution `label` ("lun") has every letter of `config` ("l", "un", ""): the one
// selection rule of the closed-form solvers (PUMA and UR).
bool ik_config_matches(std::string_view label, std::string_view config);

// All 8 solutions in the order lun, luf, ldn, ldf, run, ruf, rdn, rdf, or those matching
// `config` (full or partial; must pass check_ik_config). Unreachable: no solutions, status
// kUnreachable and a message saying why. Singular (wrist q5 ~ 0, elbow stretched/folded,
// wrist centre on joint 1's axis): the solutions are returned flagged `singular`, status
// kSingular, the message names the singularity. Never NaN.
AnalyticIkResult solve_analytic_ik(const RobotModel& model, const PumaGeometry& geometry,
                                   const Eigen::Isometry3d& T_base_tool,
                                   std::string_view config = "");

// [SECTION] Allocation-free core, for the hot path and the benchmark.

enum class PumaSingularity : unsigned {
  kNone = 0,
  kWrist = 1,     // theta5 ~ 0 (or pi): joints 4 and 6 aligned
  kElbow = 2,     // arm fully stretched or folded: 'u' and 'd' coincide
  kShoulder = 4,  // wrist centre on the shoulder-offset cylinder / joint 1's axis
};

// The texts of the singularities set in `bits` (PumaSingularity), joined by "; " in the order
// wrist, elbow, shoulder: one message composition for every closed form, each arm giving its
// own explanation of what coincides.
std::string singularity_message(unsigned bits, std::string_view wrist, std::string_view elbow,
                                std::string_view shoulder);

// Why a target is out of reach (kReachable otherwise).
enum class PumaReach {
  kReachable,
  kNotFinite,       // the target pose has a NaN or infinite entry
  kInsideCylinder,  // wrist centre closer to joint 1's axis than the shoulder offset
  kTooFar,          // wrist centre beyond a2 + hypot(a3, d4) from the shoulder
  kTooClose,        // wrist centre within | |a2| - hypot(a3, d4) | of the shoulder
};

struct PumaIkSolutions {
  static constexpr int kCount = 8;
  // Index bits: 4 = 'r' (else 'l'), 2 = 'd' (else 'u'), 1 = 'f' (else 'n').
  static constexpr std::array<const char*, 8> kConfigs = {"lun", "luf", "ldn", "ldf",
                                                          "run", "ruf", "rdn", "rdf"};
  PumaReach reach = PumaReach::kReachable;
  bool reachable() const { return reach == PumaReach::kReachable; }
  std::array<Vector6d, 8> q;              // rad, wrapped to (-pi, pi]
  std::array<unsigned, 8> singularity{};  // PumaSingularity bits per solution
  std::array<bool, 8> within_limits{};    // 2*pi equivalents considered
  double wrist_distance = 0.0;            // m, wrist centre from the shoulder in the arm's plane
  double axis_distance = 0.0;             // m, wrist centre from joint 1's axis
};

// All 8 solutions into `out`; no allocation, no exceptions.
void solve_puma_ik(const PumaGeometry& geometry, const Eigen::Isometry3d& T_base_tool,
                   PumaIkSolutions& out);

}  // namespace telear::core
