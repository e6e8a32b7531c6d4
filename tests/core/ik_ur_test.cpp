// The UR class's closed form (core/ik_ur.hpp) on the shipped ur6 (a URDF arm) and on the
// same geometry built in code from its DH table and with reversed axes: round trips of every
// branch, the branch count against the numeric search, labels, singular and unreachable
// targets, and the dispatch (solve_ik_all, solve_ik_nearest).
#include "telear/core/ik_ur.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <initializer_list>
#include <numbers>
#include <random>
#include <set>

#include "telear/core/angles.hpp"
#include "telear/core/ik_branches.hpp"
#include "telear/core/ik_listing.hpp"
#include "telear/core/inverse_kinematics.hpp"
#include "telear/core/joint_limits.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/motion_command.hpp"
#include "telear/core/pose.hpp"
#include "telear/core/robot_description.hpp"
#include "test_arms.hpp"
#include "test_util/test_util.hpp"

namespace telear::core {
namespace {

using test::kPi;
using ::testing::HasSubstr;

RobotModelPtr shipped(const char* name) {
  auto d = load_robot_description({name, "", {}});
  EXPECT_TRUE(d) << d.error().message;
  return d ? d->model : nullptr;
}

double wrapped(double a) {
  return std::remainder(a, 2.0 * kPi);
}

bool same_modulo_turns(const Eigen::VectorXd& a, const Eigen::VectorXd& b, double tolerance) {
  for (int j = 0; j < a.size(); ++j) {
    if (std::abs(wrapped(a[j] - b[j])) > tolerance) return false;
  }
  return true;
}

// Largest of the position (m) and orientation (rad) error of FK(q) against T.
double round_trip_error(const RobotModel& model, const Eigen::VectorXd& q,
                        const Eigen::Isometry3d& T) {
  const Vector6d e = pose_error_in_base(tool_pose(model, q), T);
  return std::max(e.head<3>().norm(), e.tail<3>().norm());
}

// The UR-type DH arm with the given joints turning the other way (before * Rx(pi), Rx(pi)^-1
// * after: the same links, the axis reversed), so that axes 3 and 4 can be opposite to 2.
RobotModel reversed(const RobotModel& model, std::initializer_list<int> joints) {
  RobotModel::Description d;
  d.name = model.name() + "_reversed";
  d.joints = model.joints();
  d.T_flange_tool = model.T_flange_tool();
  const Eigen::Isometry3d flip(Eigen::AngleAxisd(kPi, Eigen::Vector3d::UnitX()));
  for (int j : joints) {
    Joint& joint = d.joints[static_cast<size_t>(j)];
    joint.before = joint.before * flip;
    joint.after = flip.inverse() * joint.after;
    joint.offset = -joint.offset;
  }
  return *RobotModel::create(std::move(d));
}

// Every branch of random reachable poses: FK(IK(T)) = T to 1e-10, the generating
// configuration among them, joints within (-pi, pi], nothing NaN.
void expect_round_trips(const RobotModel& model, int poses, unsigned seed) {
  auto g = ur_geometry(model);
  ASSERT_TRUE(g) << g.error().message;
  std::mt19937_64 rng(seed);
  int branches = 0;
  for (int i = 0; i < poses; ++i) {
    const Eigen::VectorXd q_true = test::random_configuration(model, rng);
    const Eigen::Isometry3d T = tool_pose(model, q_true);
    const AnalyticIkResult r = solve_ur_analytic_ik(model, *g, T);
    ASSERT_NE(r.status, IkStatus::kUnreachable) << r.message << " q = " << q_true.transpose();
    bool found = false;
    for (const IkSolution& s : r.solutions) {
      ++branches;
      ASSERT_TRUE(s.q.allFinite()) << s.config;
      EXPECT_LE(round_trip_error(model, s.q, T), 1e-10)
          << model.name() << " " << s.config << " q_true = " << q_true.transpose();
      EXPECT_LE(s.q.cwiseAbs().maxCoeff(), kPi + 1e-12);
      found = found || same_modulo_turns(s.q, q_true, 1e-6);
    }
    EXPECT_TRUE(found) << model.name() << " q_true = " << q_true.transpose();
  }
  EXPECT_GE(branches, 4 * poses);  // most random poses have 6 or 8
}

TEST(UrGeometry, RecognisesTheShippedArmAndTheDhOne) {
  const RobotModelPtr ur6 = shipped("ur6");
  ASSERT_TRUE(ur6);
  auto g = ur_geometry(*ur6);
  ASSERT_TRUE(g) << g.error().message;
  // The published UR5 numbers, read back from the URDF's joints.
  EXPECT_NEAR(g->upper_arm, 0.425, 1e-12);
  EXPECT_NEAR(g->forearm, 0.39225, 1e-12);
  EXPECT_NEAR(std::abs(g->shoulder_offset), 0.10915, 1e-12);
  auto dh = ur_geometry(test_arms::ur_type());
  ASSERT_TRUE(dh) << dh.error().message;
  EXPECT_NEAR(dh->upper_arm, 0.425, 1e-12);
  EXPECT_NEAR(std::abs(dh->shoulder_offset), 0.10915, 1e-12);
}

TEST(UrGeometry, RefusesOtherArmsNamingTheCondition) {
  EXPECT_EQ(ur_geometry(*test::puma560()).error().message,
            "robot 'puma560' is not of the UR class (closed-form IK): the axes of joints 2 and 4 "
            "are not parallel (90.00 deg apart)");
  const RobotModelPtr arm7 = shipped("arm7");
  ASSERT_TRUE(arm7);
  EXPECT_EQ(ur_geometry(*arm7).error().message,
            "robot 'arm7' is not of the UR class (closed-form IK): it has 7 joints, needs 6");
  // Axes 5 and 6 moved apart: no wrist point.
  const RobotModel ur = test_arms::ur_type();
  RobotModel::Description d;
  d.name = "offset_wrist";
  d.joints = ur.joints();
  d.joints[5].before = Eigen::Translation3d(0.02, 0.0, 0.0) * d.joints[5].before;
  auto offset = RobotModel::create(d);
  ASSERT_TRUE(offset);
  EXPECT_EQ(ur_geometry(*offset).error().message,
            "robot 'offset_wrist' is not of the UR class (closed-form IK): the axes of joints 5 "
            "and 6 do not intersect (they pass 0.0200 m apart)");
  // Joint 5's axis tilted: not perpendicular to the parallel ones.
  d.joints = ur.joints();
  d.joints[4].before = Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()) * d.joints[4].before;
  auto tilted = RobotModel::create(d);
  ASSERT_TRUE(tilted);
  EXPECT_THAT(ur_geometry(*tilted).error().message,
              HasSubstr("the axes of joints 5 and 2 are not perpendicular"));
}

TEST(UrIk, EveryBranchRoundTripsOnTheShippedUr6) {
  const RobotModelPtr ur6 = shipped("ur6");
  ASSERT_TRUE(ur6);
  expect_round_trips(*ur6, 300, 7);
}

TEST(UrIk, EveryBranchRoundTripsOnTheDhArmAndWithReversedAxes) {
  const RobotModel ur = test_arms::ur_type();
  expect_round_trips(ur, 100, 8);
  // Axes 3 and 4 opposite to axis 2 (signs in theta = q2 + s3 q3 + s4 q4), 1, 5 and 6 reversed.
  expect_round_trips(reversed(ur, {2, 3}), 100, 9);
  expect_round_trips(reversed(ur, {0, 2, 4, 5}), 100, 10);
}

// The closed form lists exactly the branches the numeric search finds: the same count, each
// matching one found branch, at random poses away from singularities.
TEST(UrIk, BranchCountMatchesTheNumericSearch) {
  const RobotModelPtr ur6 = shipped("ur6");
  ASSERT_TRUE(ur6);
  const UrGeometry g = *ur_geometry(*ur6);
  std::mt19937_64 rng(11);
  KinematicsData data(*ur6);
  int checked = 0;
  std::set<size_t> counts;
  while (checked < 20) {
    const Eigen::VectorXd q_true = test::random_configuration(*ur6, rng);
    if (jacobian_min_singular_value(*ur6, data, q_true) < 0.02) continue;
    ++checked;
    const Eigen::Isometry3d T = tool_pose(*ur6, q_true);
    const AnalyticIkResult closed = solve_ur_analytic_ik(*ur6, g, T);
    auto searched = search_ik_branches(*ur6, T);
    ASSERT_TRUE(searched) << searched.error().message;
    ASSERT_EQ(closed.solutions.size(), searched->size()) << "q_true = " << q_true.transpose();
    counts.insert(searched->size());
    for (const IkSolution& a : closed.solutions) {
      int matches = 0;
      for (const IkSolution& b : *searched) matches += same_modulo_turns(a.q, b.q, 1e-6);
      EXPECT_EQ(matches, 1) << a.config << " q_true = " << q_true.transpose();
    }
  }
  EXPECT_TRUE(counts.count(8)) << "no pose with all eight branches";
}

// 'l'/'r', 'u'/'d', 'n'/'f' mean what ik_ur.hpp says, checked on the arm's own frames.
TEST(UrIk, LabelsFollowTheGeometry) {
  const RobotModelPtr ur6 = shipped("ur6");
  ASSERT_TRUE(ur6);
  const RobotModel& model = *ur6;
  const UrGeometry g = *ur_geometry(model);
  KinematicsData data(model);
  std::mt19937_64 rng(12);
  for (int i = 0; i < 50; ++i) {
    const Eigen::Isometry3d T = tool_pose(model, test::random_configuration(model, rng));
    const AnalyticIkResult r = solve_ur_analytic_ik(model, g, T);
    for (const IkSolution& s : r.solutions) {
      if (s.singular) continue;
      forward_kinematics(model, data, s.q);
      // Axis i's line in the base frame, now.
      auto axis_frame = [&](int j) { return data.T_base_link[j] * model.joint(j).before; };
      const Eigen::Vector3d w1 = axis_frame(0).linear().col(2);
      const Eigen::Vector3d n = axis_frame(1).linear().col(2);
      const Eigen::Vector3d p1 = axis_frame(0).translation();
      const Eigen::Vector3d wrist = T * g.wrist_in_tool;
      // Shoulder: the wrist point on the +(n x w1) side of the plane of axis 1 along n.
      const double side = n.cross(w1).dot(wrist - p1);
      EXPECT_EQ(s.config[0] == 'l', side > 0.0) << s.config << " side " << side;
      // Elbow: axis 3 on the +w1 side of the line from axis 2 to axis 4 (across n).
      const auto across = [&](const Eigen::Vector3d& v) { return v - n.dot(v) * n; };
      const Eigen::Vector3d p2 = axis_frame(1).translation();
      const Eigen::Vector3d line = across(axis_frame(3).translation() - p2).normalized();
      const Eigen::Vector3d elbow = across(axis_frame(2).translation() - p2);
      const double lift = w1.dot(elbow - line.dot(elbow) * line);
      EXPECT_EQ(s.config[1] == 'u', lift >= 0.0) << s.config << " lift " << lift;
      // Wrist: q5 - phi5 in [0, pi] for 'n'.
      const double from_singular = wrapped(s.q[4] - g.wrist_zero_angle);
      EXPECT_EQ(s.config[2] == 'n', from_singular >= 0.0) << s.config;
    }
  }
}

TEST(UrIk, SingularPosesGiveFlaggedRoundTripsWithoutNaN) {
  const RobotModelPtr ur6 = shipped("ur6");
  ASSERT_TRUE(ur6);
  const RobotModel& model = *ur6;
  const UrGeometry g = *ur_geometry(model);
  struct Case {
    const char* what;
    Eigen::VectorXd q;
    const char* message;
  };
  const auto deg = [](std::initializer_list<double> values) {
    Eigen::VectorXd q(6);
    int i = 0;
    for (double v : values) q[i++] = radians_from_degrees(v);
    return q;
  };
  const std::vector<Case> cases = {
      // q5 = 0: axis 6 parallel to axes 2-4.
      {"wrist", deg({10, -80, 70, -40, 0, 30}), "wrist singularity"},
      // q3 = 0: upper arm and forearm in line (stretched).
      {"elbow", deg({20, -60, 0, -50, 60, 10}), "elbow singularity"},
      // The named "zero" configuration: stretched along -x, wrist singular too.
      {"zero", *model.named_configuration("zero"), "elbow singularity"},
  };
  for (const Case& c : cases) {
    const Eigen::Isometry3d T = tool_pose(model, c.q);
    const AnalyticIkResult r = solve_ur_analytic_ik(model, g, T, "", c.q);
    EXPECT_EQ(r.status, IkStatus::kSingular) << c.what;
    EXPECT_THAT(r.message, HasSubstr(c.message)) << c.what;
    ASSERT_FALSE(r.solutions.empty()) << c.what;
    bool found = false;
    for (const IkSolution& s : r.solutions) {
      ASSERT_TRUE(s.q.allFinite()) << c.what << " " << s.config;
      EXPECT_LE(round_trip_error(model, s.q, T), 1e-10) << c.what << " " << s.config;
      found = found || same_modulo_turns(s.q, c.q, 1e-6);
    }
    // Given the free joints of c.q, the singular branch is c.q itself.
    EXPECT_TRUE(found) << c.what;
  }
  // The shoulder singularity: the wrist point in the plane of axis 1 along n (the two
  // shoulder solutions meet). Built from the wrist point: T moved so that W lies in it.
  Eigen::VectorXd q = deg({0, -100, 80, -60, 70, 20});
  Eigen::Isometry3d T = tool_pose(model, q);
  const Eigen::Vector3d W = T * g.wrist_in_tool;
  const Eigen::Vector3d toward = g.w1_cross_n;  // q1 = 0: n(q1) = n
  T.pretranslate(-toward.dot(W - g.point[0]) * toward);
  const AnalyticIkResult shoulder = solve_ur_analytic_ik(model, g, T);
  EXPECT_EQ(shoulder.status, IkStatus::kSingular);
  EXPECT_THAT(shoulder.message, HasSubstr("shoulder singularity"));
  ASSERT_FALSE(shoulder.solutions.empty());
  for (const IkSolution& s : shoulder.solutions) {
    ASSERT_TRUE(s.q.allFinite()) << s.config;
    EXPECT_LE(round_trip_error(model, s.q, T), 1e-10) << s.config;
  }
  // Near (not at) the wrist singularity: q5 = 1e-9 rad, still exact.
  q = deg({10, -80, 70, -40, 0, 30});
  q[4] = 1e-9;
  const Eigen::Isometry3d near_T = tool_pose(model, q);
  for (const IkSolution& s : solve_ur_analytic_ik(model, g, near_T).solutions) {
    EXPECT_LE(round_trip_error(model, s.q, near_T), 1e-10) << s.config;
  }
}

TEST(UrIk, UnreachableTargetsSayWhy) {
  const RobotModelPtr ur6 = shipped("ur6");
  ASSERT_TRUE(ur6);
  const RobotModel& model = *ur6;
  const UrGeometry g = *ur_geometry(model);
  const auto at = [](double x, double y, double z) {
    return pose_from_xyz_rpy({x, y, z}, {kPi, 0.0, 0.0});
  };
  const AnalyticIkResult far = solve_ur_analytic_ik(model, g, at(2.0, 0.0, 0.3));
  EXPECT_EQ(far.status, IkStatus::kUnreachable);
  EXPECT_TRUE(far.solutions.empty());
  EXPECT_THAT(far.message, HasSubstr("target unreachable: in every branch the wrist-1 axis "
                                     "would be beyond the arm's reach of 0.817"));
  EXPECT_THAT(far.message, HasSubstr(" m from the shoulder axis (nearest: 1."));
  // Pointing down right above the base: the wrist point on joint 1's axis.
  Eigen::Isometry3d inside = at(0.0, 0.0, 0.5);
  const Eigen::Vector3d off_axis = inside * g.wrist_in_tool - g.point[0];
  inside.pretranslate(-Eigen::Vector3d(off_axis.x(), off_axis.y(), 0.0));  // axis 1 is z
  const AnalyticIkResult cylinder = solve_ur_analytic_ik(model, g, inside);
  EXPECT_EQ(cylinder.status, IkStatus::kUnreachable);
  EXPECT_THAT(cylinder.message,
              HasSubstr("target unreachable: the wrist point is 0.0000 m from joint 1's axis, "
                        "inside the shoulder-offset cylinder of radius 0.109"));
  Eigen::Isometry3d nan = at(0.4, 0.1, 0.3);
  nan(1, 3) = std::nan("");
  const AnalyticIkResult bad = solve_ur_analytic_ik(model, g, nan);
  EXPECT_EQ(bad.message, "target pose is not finite");
  auto all = solve_ik_all(model, at(2.0, 0.0, 0.3));
  ASSERT_FALSE(all);
  EXPECT_THAT(all.error().message, HasSubstr("solve_ik_all: target unreachable: in every branch"));
}

// At a singular pose branches meet: solve_ik_all lists each once (like the numeric search,
// within its distinct tolerance), every one reaching the pose.
TEST(UrIk, SolveIkAllListsMeetingBranchesOnce) {
  const RobotModelPtr ur6 = shipped("ur6");
  ASSERT_TRUE(ur6);
  const RobotModel& model = *ur6;
  // q3 = 0 (elbow stretched: 'u' = 'd') and q5 = 0 (wrist: 'n' = 'f' with q6 given).
  Eigen::VectorXd q(6);
  q << 0.3, -1.0, 0.0, -0.8, 0.0, 0.4;
  const Eigen::Isometry3d T = tool_pose(model, q);
  auto all = solve_ik_all(model, T);
  ASSERT_TRUE(all) << all.error().message;
  EXPECT_LT(all->size(), 8u);
  EXPECT_GE(all->size(), 1u);
  // This shoulder's four meet in one, flagged; the other shoulder puts the wrist elsewhere,
  // where its branches are regular.
  int singular = 0;
  bool found = false;
  for (size_t i = 0; i < all->size(); ++i) {
    const IkSolution& s = (*all)[i];
    singular += s.singular;
    // q's branch: q6 is solve_ik_all's free value (0) there, q4 turned to make up for it.
    found = found || (std::abs(wrapped(s.q[0] - q[0])) < 1e-6 && std::abs(wrapped(s.q[2])) < 1e-6 &&
                      std::abs(wrapped(s.q[4])) < 1e-6);
    EXPECT_LE(round_trip_error(model, s.q, T), 1e-10) << s.config;
    for (size_t k = 0; k < i; ++k) {
      EXPECT_FALSE(same_modulo_turns(s.q, (*all)[k].q, 1e-4)) << s.config << " repeats";
    }
  }
  EXPECT_GE(singular, 1);
  EXPECT_TRUE(found) << "q's branch is missing";
}

// solve_ik_all lists the closed form's branches for ur6 (labelled like the PUMA's), and
// solve_ik_nearest picks the nearest of them within the limits.
TEST(UrIk, DispatchUsesTheClosedForm) {
  const RobotModelPtr ur6 = shipped("ur6");
  ASSERT_TRUE(ur6);
  const RobotModel& model = *ur6;
  // The first of a seeded series of random poses with all eight branches.
  const UrGeometry g = *ur_geometry(model);
  std::mt19937_64 pick(3);
  Eigen::Isometry3d T;
  do {
    T = tool_pose(model, test::random_configuration(model, pick));
  } while (solve_ur_analytic_ik(model, g, T).solutions.size() != 8);
  auto all = solve_ik_all(model, T);
  ASSERT_TRUE(all) << all.error().message;
  ASSERT_EQ(all->size(), 8u);
  const std::vector<std::string> labels = {"lun", "luf", "ldn", "ldf", "run", "ruf", "rdn", "rdf"};
  for (size_t i = 0; i < 8; ++i) {
    EXPECT_EQ((*all)[i].config, labels[i]);
    EXPECT_LE(round_trip_error(model, (*all)[i].q, T), 1e-10);
    EXPECT_TRUE((*all)[i].within_limits);  // ur6 turns +-360 deg
  }
  // The numeric search stays reachable by name: "b0" ... and the same set.
  auto searched = search_ik_branches(model, T);
  ASSERT_TRUE(searched);
  ASSERT_EQ(searched->size(), 8u);
  EXPECT_EQ(searched->front().config, "b0");

  std::mt19937_64 rng(5);
  KinematicsData data(model);
  for (int trial = 0; trial < 100; ++trial) {
    const Eigen::VectorXd q_current = test::random_configuration(model, rng);
    Eigen::VectorXd q_target = q_current;
    q_target.array() += 0.02;
    if (!within_limits(model, q_target)) continue;
    // Next to a singularity another branch may be nearer than the one the move stayed on.
    if (jacobian_min_singular_value(model, data, q_target) < 0.05) continue;
    const Eigen::Isometry3d target = tool_pose(model, q_target);
    auto r = solve_ik_nearest(model, target, q_current);
    ASSERT_TRUE(r) << r.error().message;
    EXPECT_EQ(r->config.size(), 3u) << r->config;  // a closed-form label, not "numeric"
    EXPECT_TRUE(within_limits(model, r->q));
    EXPECT_LE(round_trip_error(model, r->q, target), 1e-10);
    // Away from singularities the nearest branch is the one the small move stayed on.
    EXPECT_LE((r->q - q_target).cwiseAbs().maxCoeff(), 1e-8) << trial;
  }
  // At the wrist singularity q6 stays where it is (only q6 and q2 + q3 + q4 together are
  // determined), so a pure translation does not spin the tool flange.
  Eigen::VectorXd q_singular(6);
  q_singular << 0.1, -1.4, 1.2, -0.7, 0.0, 0.5;
  Eigen::Isometry3d moved = tool_pose(model, q_singular);
  moved.pretranslate(Eigen::Vector3d(0.0, 0.0, 0.01));
  auto r = solve_ik_nearest(model, moved, q_singular);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_LE(round_trip_error(model, r->q, moved), 1e-10);
  EXPECT_NEAR(r->q[5], 0.5, 1e-12);
}

// What `telear kin ik` lists (core/ik_listing.hpp): ur6's closed-form branches, and --config
// selecting among them; an arm with neither closed form says why it has neither.
TEST(UrIk, TheKinListingUsesTheClosedForm) {
  const RobotModelPtr ur6 = shipped("ur6");
  ASSERT_TRUE(ur6);
  const Eigen::Isometry3d T = tool_pose(*ur6, *ur6->named_configuration("ready"));
  auto listing = list_ik_solutions(*ur6, T);
  ASSERT_TRUE(listing) << listing.error().message;
  EXPECT_TRUE(listing->closed_form);
  ASSERT_FALSE(listing->result.solutions.empty());
  for (const IkSolution& s : listing->result.solutions) {
    EXPECT_EQ(s.config.size(), 3u) << s.config;
    EXPECT_LE(round_trip_error(*ur6, s.q, T), 1e-10) << s.config;
  }
  const std::string first = listing->result.solutions.front().config;
  auto one = list_ik_solutions(*ur6, T, first);
  ASSERT_TRUE(one) << one.error().message;
  ASSERT_EQ(one->result.solutions.size(), 1u);
  EXPECT_EQ(one->result.solutions[0].config, first);
  const RobotModelPtr arm7 = shipped("arm7");
  ASSERT_TRUE(arm7);
  EXPECT_EQ(list_ik_solutions(*arm7, tool_pose(*arm7, *arm7->named_configuration("home")), "lun")
                .error()
                .message,
            "config selects closed-form solutions, and robot 'arm7' has no standard DH table "
            "(the PUMA class's closed form reads one; a URDF arm has the UR class's, ik_ur.hpp, "
            "or numeric IK); robot 'arm7' is not of the UR class (closed-form IK): it has 7 "
            "joints, needs 6");
}

}  // namespace
}  // namespace telear::core
