#include "telear/core/ik_branches.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "telear/core/kinematics.hpp"
#include "telear/core/motion_command.hpp"
#include "telear/core/pose.hpp"
#include "test_arms.hpp"
#include "test_util/test_util.hpp"

namespace telear::core {
namespace {

using ::testing::HasSubstr;

double wrapped(double a) {
  return std::remainder(a, 2.0 * std::numbers::pi);
}

bool same_modulo_turns(const Eigen::VectorXd& a, const Eigen::VectorXd& b, double tolerance) {
  for (int j = 0; j < a.size(); ++j) {
    if (std::abs(wrapped(a[j] - b[j])) > tolerance) return false;
  }
  return true;
}

// Generic reachable poses of the UR-type arm: FK of random configurations away from its
// singularities (smallest Jacobian singular value above 0.02).
std::vector<Eigen::VectorXd> generic_configurations(const RobotModel& model, int count) {
  std::mt19937_64 rng(42);
  KinematicsData data(model);
  std::vector<Eigen::VectorXd> out;
  while (static_cast<int>(out.size()) < count) {
    Eigen::VectorXd q = test::random_configuration(model, rng);
    if (jacobian_min_singular_value(model, data, q) > 0.02) out.push_back(q);
  }
  return out;
}

// Checks one listing: labels, flags, round trip FK(IK(T)) = T, distinct branches, and the
// configuration the pose was made from among them.
void expect_valid_listing(const RobotModel& model, const Eigen::VectorXd& q_true,
                          const std::vector<IkSolution>& all) {
  const Eigen::Isometry3d T = tool_pose(model, q_true);
  bool contains_q_true = false;
  for (size_t i = 0; i < all.size(); ++i) {
    const IkSolution& s = all[i];
    std::string label = "b";
    label += std::to_string(i);
    EXPECT_EQ(s.config, label);
    EXPECT_TRUE(s.within_limits);
    const Vector6d e = pose_error_in_base(tool_pose(model, s.q), T);
    EXPECT_LT(e.head<3>().norm(), 1e-9) << s.config;
    EXPECT_LT(e.tail<3>().norm(), 1e-9) << s.config;
    for (size_t k = 0; k < i; ++k) {
      EXPECT_FALSE(same_modulo_turns(s.q, all[k].q, 1e-4)) << s.config << " repeats";
    }
    contains_q_true = contains_q_true || same_modulo_turns(s.q, q_true, 1e-6);
  }
  EXPECT_TRUE(contains_q_true) << "the configuration the pose was made from is missing";
}

// Poses in the middle of the UR's workspace, where all 8 branches (2 shoulders x 2 wrists x
// 2 elbows) exist.
TEST(IkBranches, FindsAllEightBranchesOfGenericUrTypePoses) {
  const RobotModel model = test_arms::ur_type();
  const double configurations[][6] = {
      {0.3, -1.2, 1.4, -0.9, 1.1, 0.5}, {-0.4, -1.9, 1.1, 0.3, -0.8, 2.0},
      {0.2, -1.1, 1.3, -0.7, 1.2, 0.4}, {1.0, -0.8, -1.5, -2.0, 0.9, -1.0},
      {2.5, -2.2, 0.9, 1.2, -1.4, 0.3}, {-1.3, -0.6, 1.9, -1.0, 2.0, -2.5}};
  for (const auto& values : configurations) {
    const Eigen::VectorXd q_true = Eigen::Map<const Eigen::VectorXd>(values, 6);
    auto all = search_ik_branches(model, tool_pose(model, q_true));
    ASSERT_TRUE(all) << all.error().message;
    EXPECT_EQ(all->size(), 8u) << "q_true = " << q_true.transpose();
    expect_valid_listing(model, q_true, *all);
    for (const IkSolution& s : *all) EXPECT_FALSE(s.singular) << s.config;
  }
}

// Random poses (away from singularities) have 2, 4, 6 or 8 real branches, depending on which
// elbow triangles close; the default search finds as many as one with ten times the seeds.
TEST(IkBranches, DefaultSearchIsAsCompleteAsALongerOneOnRandomPoses) {
  const RobotModel model = test_arms::ur_type();
  IkBranchOptions longer;
  longer.attempts = 1000;
  int eights = 0;
  for (const Eigen::VectorXd& q_true : generic_configurations(model, 25)) {
    const Eigen::Isometry3d T = tool_pose(model, q_true);
    auto all = search_ik_branches(model, T);
    auto more = search_ik_branches(model, T, longer);
    ASSERT_TRUE(all && more) << q_true.transpose();
    EXPECT_EQ(all->size(), more->size()) << q_true.transpose();
    EXPECT_EQ(all->size() % 2, 0u);
    EXPECT_LE(all->size(), 8u);
    if (all->size() == 8) ++eights;
    expect_valid_listing(model, q_true, *all);
  }
  EXPECT_GE(eights, 12);  // most of the workspace has all eight
}

TEST(IkBranches, MatchesThePumaClosedForm) {
  const RobotModelPtr puma = test::puma560();
  const PumaGeometry geometry = *puma_geometry(*puma);
  Eigen::VectorXd q(6);
  q << 0.3, 0.5, -0.4, 0.6, 0.7, -0.2;
  const Eigen::Isometry3d T = tool_pose(*puma, q);
  const AnalyticIkResult analytic = solve_analytic_ik(*puma, geometry, T);
  ASSERT_EQ(analytic.solutions.size(), 8u);
  auto numeric = search_ik_branches(*puma, T);
  ASSERT_TRUE(numeric) << numeric.error().message;
  ASSERT_EQ(numeric->size(), 8u);
  for (const IkSolution& a : analytic.solutions) {
    int matches = 0;
    for (const IkSolution& b : *numeric) {
      if (same_modulo_turns(a.q, b.q, 1e-7)) {
        ++matches;
        EXPECT_EQ(a.within_limits, b.within_limits) << a.config << " vs " << b.config;
      }
    }
    EXPECT_EQ(matches, 1) << a.config;
  }
}

// solve_ik_all takes the closed form where the arm has one: the PUMA's eight and the UR
// class's (tests/core/ik_ur_test.cpp), labelled, in label order, moved into the limits.
TEST(IkBranches, SolveIkAllUsesTheClosedFormWhereThereIsOne) {
  const RobotModelPtr puma = test::puma560();
  Eigen::VectorXd q(6);
  q << 0.3, 0.5, -0.4, 0.6, 0.7, -0.2;
  const Eigen::Isometry3d T = tool_pose(*puma, q);
  const AnalyticIkResult analytic = solve_analytic_ik(*puma, *puma_geometry(*puma), T);
  auto all = solve_ik_all(*puma, T);
  ASSERT_TRUE(all) << all.error().message;
  ASSERT_EQ(all->size(), analytic.solutions.size());
  for (size_t i = 0; i < all->size(); ++i) {
    EXPECT_EQ((*all)[i].config, analytic.solutions[i].config);
    EXPECT_TRUE(same_modulo_turns((*all)[i].q, analytic.solutions[i].q, 1e-12));
    EXPECT_EQ((*all)[i].within_limits, analytic.solutions[i].within_limits);
  }
  const RobotModel narrow = test_arms::ur_type(-0.5, 0.5);
  q << 0.2, -1.1, 1.3, -0.7, 1.2, 0.4;
  auto ur = solve_ik_all(narrow, tool_pose(narrow, q));
  ASSERT_TRUE(ur) << ur.error().message;
  ASSERT_EQ(ur->size(), 8u);
  EXPECT_EQ(ur->front().config, "lun");
  EXPECT_EQ(ur->back().config, "rdf");
  int inside = 0;
  for (const IkSolution& s : *ur) {
    EXPECT_EQ(s.within_limits, std::abs(wrapped(s.q[0])) <= 0.5) << s.config;
    if (s.within_limits) {
      EXPECT_LE(std::abs(s.q[0]), 0.5) << s.config;
    }
    inside += s.within_limits;
  }
  EXPECT_EQ(inside, 4);  // one shoulder's four
}

TEST(IkBranches, ListsBranchesOutsideTheLimitsFlagged) {
  const RobotModel free = test_arms::ur_type();
  const RobotModel narrow = test_arms::ur_type(-0.5, 0.5);  // shoulder pan limited
  Eigen::VectorXd q(6);
  q << 0.2, -1.1, 1.3, -0.7, 1.2, 0.4;
  const Eigen::Isometry3d T = tool_pose(free, q);
  auto all_free = search_ik_branches(free, T);
  auto all_narrow = search_ik_branches(narrow, T);
  ASSERT_TRUE(all_free && all_narrow);
  ASSERT_EQ(all_narrow->size(), 8u);
  int inside = 0;
  for (size_t i = 0; i < all_narrow->size(); ++i) {
    const IkSolution& s = (*all_narrow)[i];
    EXPECT_TRUE(same_modulo_turns(s.q, (*all_free)[i].q, 1e-7)) << s.config;
    const bool pan_inside = std::abs(wrapped(s.q[0])) <= 0.5;
    EXPECT_EQ(s.within_limits, pan_inside) << s.config << " q1 = " << s.q[0];
    if (s.within_limits) {
      ++inside;
      EXPECT_LE(std::abs(s.q[0]), 0.5);
    }
  }
  EXPECT_GE(inside, 1);  // q itself
  EXPECT_LT(inside, 8);  // the other shoulder (q1 + pi about) is outside
}

TEST(IkBranches, IsDeterministicAndSorted) {
  const RobotModel model = test_arms::ur_type();
  Eigen::VectorXd q(6);
  q << -0.4, -1.9, 1.1, 0.3, -0.8, 2.0;
  const Eigen::Isometry3d T = tool_pose(model, q);
  auto a = search_ik_branches(model, T);
  auto b = search_ik_branches(model, T);
  ASSERT_TRUE(a && b);
  ASSERT_EQ(a->size(), b->size());
  for (size_t i = 0; i < a->size(); ++i) {
    EXPECT_EQ((*a)[i].q, (*b)[i].q);
    if (i > 0) {
      // Sorted on the wrapped values; the first joint decides unless equal (within the
      // distinct tolerance, 1e-4).
      EXPECT_LE(wrapped((*a)[i - 1].q[0]), wrapped((*a)[i].q[0]) + 1e-4);
    }
  }
  // Another seed finds the same set in the same order.
  IkBranchOptions other;
  other.seed = 12345;
  auto c = search_ik_branches(model, T, other);
  ASSERT_TRUE(c);
  ASSERT_EQ(c->size(), a->size());
  for (size_t i = 0; i < a->size(); ++i) {
    EXPECT_TRUE(same_modulo_turns((*a)[i].q, (*c)[i].q, 1e-7)) << i;
  }
}

TEST(IkBranches, RejectsBadInputWithMessages) {
  const RobotModel model = test_arms::ur_type();
  const Eigen::Isometry3d T = tool_pose(model, Eigen::VectorXd::Constant(6, 0.3));
  IkBranchOptions o;
  o.attempts = 0;
  auto r = search_ik_branches(model, T, o);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().message, "IkBranchOptions::attempts must be positive, got 0");
  o = {};
  o.distinct_tolerance_rad = -1.0;
  EXPECT_THAT(check_ik_branch_options(o).error().message,
              HasSubstr("IkBranchOptions::distinct_tolerance_rad must be positive"));
  o = {};
  o.position_tolerance_m = std::nan("");
  EXPECT_THAT(check_ik_branch_options(o).error().message,
              HasSubstr("IkBranchOptions::position_tolerance_m"));

  Eigen::Isometry3d bad = T;
  bad(0, 3) = std::nan("");
  EXPECT_THAT(search_ik_branches(model, bad).error().message, HasSubstr("not finite"));

  Eigen::Isometry3d far = T;
  far.translation() = Eigen::Vector3d(3.0, 0.0, 0.0);  // reach is about 1 m
  IkBranchOptions quick;
  quick.attempts = 8;
  auto unreachable = search_ik_branches(model, far, quick);
  ASSERT_FALSE(unreachable);
  EXPECT_THAT(unreachable.error().message,
              HasSubstr("target unreachable: none of 8 seeded attempts converged"));

  const RobotModel arm7 = test_arms::panda_like();
  auto redundant = search_ik_branches(arm7, tool_pose(arm7, test_arms::panda_ready()));
  ASSERT_FALSE(redundant);
  EXPECT_THAT(redundant.error().message, HasSubstr("has 7 joints"));
  EXPECT_THAT(redundant.error().message, HasSubstr("solve_ik_nearest"));
}

}  // namespace
}  // namespace telear::core
