#pragma once
// Closed-form inverse kinematics of UR-type arms: six revolute joints whose middle three axes
// (shoulder, elbow, wrist 1) are parallel, no spherical wrist. Up to 8 solutions.
//
// The class is recognised from the arm's own joints, whatever file they came from (a DH
// table or a URDF): with every axis taken at q = 0 as a line in the base frame (direction w_i,
// a point p_i), the product of exponentials reads
//
//   T_base_tool(q) = exp(xi_1 q_1) ... exp(xi_6 q_6) M,     M = T_base_tool(0),
//
// and the arm is of the class when (tolerance 1e-9)
//   - w_2, w_3, w_4 are parallel (their common direction n = w_2; w_3, w_4 may be opposite),
//   - w_1 is perpendicular to n, and so is w_5,
//   - axes 5 and 6 are perpendicular and intersect, at the wrist point W,
//   - axes 2, 3 and 4 are distinct lines (upper arm L2 and forearm L3 > 1 micrometre).
// Nothing else is assumed: link offsets along n, a tool anywhere, DH offsets and mirrored
// axes are all allowed. The UR3/5/10 family and the shipped ur6 are of the class; the PUMA 560
// is not (its axis 4 is perpendicular to axis 3; it has ik_analytic.hpp).
//
// Solution (rotations about parallel axes add up, and leave components along n unchanged):
//   q1: W (fixed in the tool frame) lies on axis 5, every point of which has the same
//       component c along n measured from axis 1, whatever q2 ... q5: n(q1) . (W - p_1) = c
//       with n(q1) = Rot(w_1, q1) n, i.e. A cos q1 + B sin q1 = c, r = hypot(A, B) the
//       distance of W from axis 1: q1 = atan2(B, A) +- acos(c / r) ('l' +, 'r' -).
//   q5: the tool's axis-6 direction z6 satisfies n(q1) . z6 = cos(q5 - phi5), phi5 being
//       where axis 6 is parallel to n (the wrist singularity): q5 = phi5 +- beta with
//       beta = atan2(|n(q1) x z6|, n(q1) . z6) ('n' +, 'f' -).
//   q6: Rot(w_6, q6) takes R'^T n onto Rot(w_5, -q5) n, R' = Rot(w_1, q1)^T R_tool R_M^T.
//   theta = q2 + s3 q3 + s4 q4 (s_i = w_i . n = +-1): the angle of the rotation about n
//       left over, R' Rot(w_6, -q6) Rot(w_5, -q5) = Rot(n, theta).
//   q2, q3: a planar two-link problem: a point of axis 4 is carried by joints 2 and 3 only;
//       the triangle (L2, L3, distance from axis 2) gives two elbows ('u' when the elbow
//       axis lies on the +w_1 side of the line from the shoulder axis to the wrist-1 axis,
//       'd' on the other), then q2 turns the upper arm onto that line.
//   q4 = s4 (theta - q2 - s3 q3).
//
// Labels: like the PUMA's (ik_analytic.hpp) 'l'/'r' shoulder, 'u'/'d' elbow, 'n'/'f' wrist,
// same order (index bits 4 = 'r', 2 = 'd', 1 = 'f'). 'l' is the shoulder solution whose
// wrist point lies on the +(n(q1) x w_1) side of the plane through axis 1 parallel to n.
// Unlike the PUMA, which branches exist depends on the branch: each of the four (shoulder,
// wrist) pairs puts axis 4 elsewhere, so the elbow triangle may close for some and not for
// others (`valid`). At the wrist singularity (axis 6 parallel to n) only q6 + s theta is
// determined and q6 takes the given `q_free` value, or, where that leaves the elbow triangle
// open (q6 moves axis 4 on a circle then), the value nearest it that closes the triangle;
// with the wrist point on axis 1 (c = 0
// only) q1 takes its `q_free` value, and with the wrist-1 axis on the shoulder axis
// (L2 = L3 only) q2 does. Values are wrapped to (-pi, pi]. Never NaN.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <string_view>

#include "telear/core/ik_analytic.hpp"
#include "telear/core/pose.hpp"
#include "telear/core/result.hpp"
#include "telear/core/robot_model.hpp"

namespace telear::core {

// What the closed form needs, extracted once from a model (cheap to copy).
struct UrGeometry {
  std::array<Eigen::Vector3d, 6> axis;           // w_i at q = 0, unit, base frame
  std::array<Eigen::Vector3d, 6> point;          // p_i: a point of axis i at q = 0 (m)
  Eigen::Vector3d n = Eigen::Vector3d::UnitZ();  // direction of axes 2, 3, 4 (= w_2)
  Eigen::Vector3d w1_cross_n = Eigen::Vector3d::UnitX();
  double sign3 = 1.0, sign4 = 1.0;                  // w_3 . n, w_4 . n
  Eigen::Vector3d wrist = Eigen::Vector3d::Zero();  // W at q = 0, base frame
  Eigen::Vector3d wrist_in_tool = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis6_in_tool = Eigen::Vector3d::UnitZ();
  Eigen::Matrix3d R_M = Eigen::Matrix3d::Identity();  // rotation of M
  double shoulder_offset = 0.0;                       // c: n . (W - p_1) (m)
  double wrist_zero_angle = 0.0;                      // phi5 (rad)
  double upper_arm = 0.0;                             // L2: axis 2 to axis 3 (m)
  double forearm = 0.0;                               // L3: axis 3 to axis 4 (m)
  double elbow_zero_angle = 0.0;  // angle about n from the upper arm to the forearm at q = 0
  std::array<double, 6> lower{}, upper{};  // rad, joint limits
};

// The UR geometry of `model`, or an error naming the first condition above that fails
// ("robot 'puma560' is not of the UR class (closed-form IK): the axes of joints 2 and 4 are
// not parallel (90.00 deg apart)").
Result<UrGeometry> ur_geometry(const RobotModel& model);

// Why a target is out of reach; per-branch reasons are folded into the most telling one.
enum class UrReach {
  kReachable,       // at least one branch exists
  kNotFinite,       // the target pose has a NaN or infinite entry
  kInsideCylinder,  // wrist point closer to axis 1 than the shoulder offset |c|
  kTooFar,          // every branch's wrist-1 axis beyond L2 + L3 from the shoulder axis
  kTooClose,        // ... within |L2 - L3| of it (or some too far, the others too close)
};

struct UrIkSolutions {
  static constexpr int kCount = 8;
  static constexpr std::array<const char*, 8> kConfigs = {"lun", "luf", "ldn", "ldf",
                                                          "run", "ruf", "rdn", "rdf"};
  UrReach reach = UrReach::kReachable;
  bool reachable() const { return reach == UrReach::kReachable; }
  std::array<bool, 8> valid{};            // the branch exists (its elbow triangle closes)
  std::array<Vector6d, 8> q;              // rad, wrapped to (-pi, pi]; valid branches only
  std::array<unsigned, 8> singularity{};  // PumaSingularity bits (wrist, elbow, shoulder)
  std::array<bool, 8> within_limits{};    // 2*pi equivalents considered
  double axis_distance = 0.0;             // m, wrist point from axis 1
  double nearest_reach = 0.0;             // m, shoulder axis to wrist-1 axis of the closest miss
};

// All branches into `out`; no allocation, no exceptions. `q_free` gives the joints that a
// singularity leaves undetermined (q1, q2, q6; see above); the others are ignored.
void solve_ur_ik(const UrGeometry& geometry, const Eigen::Isometry3d& T_base_tool,
                 UrIkSolutions& out, const Vector6d& q_free = Vector6d::Zero());

// The labelled form: the existing branches in label order, or those matching `config`
// (check_ik_config's syntax), each polished by Newton steps where FK(q) misses the target by
// more than 1e-12 (m, rad); status kUnreachable with a message saying why when none exists,
// kSingular (solutions flagged) near a singularity.
AnalyticIkResult solve_ur_analytic_ik(const RobotModel& model, const UrGeometry& geometry,
                                      const Eigen::Isometry3d& T_base_tool,
                                      std::string_view config = "",
                                      const Vector6d& q_free = Vector6d::Zero());

}  // namespace telear::core
