#include "telear/core/inverse_kinematics.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <numbers>
#include <random>

#include "telear/core/angles.hpp"
#include "telear/core/joint_limits.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/robot_loader.hpp"
#include "test_util/test_util.hpp"

namespace telear::core {
namespace {

using test::kPi;
using test::max_abs_diff;
using ::testing::HasSubstr;

// Brute force: every 2 pi shift of every joint of every analytic solution, the nearest one
// within the limits.
std::optional<Eigen::VectorXd> brute_force_nearest(const RobotModel& model,
                                                   const Eigen::Isometry3d& T,
                                                   const Eigen::VectorXd& q_current) {
  const PumaGeometry g = *puma_geometry(model);
  std::optional<Eigen::VectorXd> best;
  double best_distance = 1e300;
  for (const IkSolution& s : solve_analytic_ik(model, g, T).solutions) {
    Eigen::VectorXd q = s.q;
    bool ok = true;
    for (int j = 0; j < 6 && ok; ++j) {
      double chosen = 0.0, chosen_distance = 1e300;
      for (int k = -2; k <= 2; ++k) {
        const double v = s.q[j] + 2 * kPi * k;
        if (v < model.lower_limits()[j] || v > model.upper_limits()[j]) continue;
        if (std::abs(v - q_current[j]) < chosen_distance) {
          chosen = v;
          chosen_distance = std::abs(v - q_current[j]);
        }
      }
      ok = chosen_distance < 1e300;
      q[j] = chosen;
    }
    if (ok && (q - q_current).squaredNorm() < best_distance) {
      best_distance = (q - q_current).squaredNorm();
      best = q;
    }
  }
  return best;
}

class NearestIk : public ::testing::Test {
 protected:
  RobotModelPtr model = test::puma560();
};

TEST_F(NearestIk, PicksTheNearestInLimitSolution) {
  std::mt19937_64 rng(31);
  int compared = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Eigen::VectorXd q_current = test::random_configuration(*model, rng);
    const Eigen::Isometry3d T = tool_pose(*model, test::random_configuration(*model, rng));
    const Result<IkSolution> r = solve_ik_nearest(*model, T, q_current);
    const auto expected = brute_force_nearest(*model, T, q_current);
    ASSERT_EQ(r.ok(), expected.has_value()) << (r ? "" : r.error().message);
    if (!r) continue;
    ++compared;
    EXPECT_TRUE(r->within_limits);
    EXPECT_TRUE(within_limits(*model, r->q));
    EXPECT_LT(max_abs_diff(tool_pose(*model, r->q).matrix(), T.matrix()), 1e-9);
    EXPECT_LT((r->q - *expected).cwiseAbs().maxCoeff(), 1e-9) << "trial " << trial;
  }
  EXPECT_GT(compared, 1900);
}

TEST_F(NearestIk, ASmallMoveStaysOnTheSameBranch) {
  std::mt19937_64 rng(32);
  int moves = 0, same = 0;
  for (int trial = 0; trial < 500; ++trial) {
    Eigen::VectorXd q_current = test::random_configuration(*model, rng);
    Eigen::VectorXd q_target = q_current;
    for (int j = 0; j < 6; ++j) q_target[j] += 0.01 * (static_cast<double>(rng() % 200) / 100 - 1);
    if (!within_limits(*model, q_target)) continue;
    const Eigen::Isometry3d T = tool_pose(*model, q_target);
    const auto r = solve_ik_nearest(*model, T, q_current);
    ASSERT_TRUE(r) << r.error().message;
    ++moves;
    EXPECT_LT(max_abs_diff(tool_pose(*model, r->q).matrix(), T.matrix()), 1e-9);
    // Never farther than the configuration that generated the target; the same one unless
    // another branch is as near (close to a singularity, where branches meet).
    EXPECT_LE((r->q - q_current).norm(), (q_target - q_current).norm() + 1e-9) << trial;
    same += (r->q - q_target).cwiseAbs().maxCoeff() < 1e-8;
  }
  EXPECT_GT(moves, 400);
  EXPECT_GE(same, moves - 2);
}

TEST_F(NearestIk, UsesTheTwoPiEquivalentOfTheWristJoints) {
  // Fixed-size vectors: a copied comma-initialised VectorXd draws GCC 12's
  // -Wmaybe-uninitialized false positive at -O1 (the tests' optimisation).
  using Vector6d = Eigen::Matrix<double, 6, 1>;
  Vector6d q;
  q << 0.1, -0.3, 0.2, radians_from_degrees(250.0), -0.6, radians_from_degrees(-240.0);
  Vector6d q_current = q;
  q_current[3] -= 0.02;
  q_current[5] += 0.02;
  const auto r = solve_ik_nearest(*model, tool_pose(*model, q), q_current);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_NEAR(r->q[3], q[3], 1e-9);  // not the wrapped -110 deg
  EXPECT_NEAR(r->q[5], q[5], 1e-9);  // not the wrapped 120 deg
}

TEST_F(NearestIk, WristSingularityKeepsJoint4Still) {
  using Vector6d = Eigen::Matrix<double, 6, 1>;
  Vector6d q;
  q << 0.2, -0.4, 0.3, 0.3, 0.0, 0.2;
  Vector6d q_current = q;
  q_current[3] = 0.7;
  const auto r = solve_ik_nearest(*model, tool_pose(*model, q), q_current);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(r->singular);
  EXPECT_NEAR(r->q[3], 0.7, 1e-12);
  EXPECT_NEAR(r->q[3] + r->q[5], 0.5, 1e-9);
  EXPECT_LT(max_abs_diff(tool_pose(*model, r->q).matrix(), tool_pose(*model, q).matrix()), 1e-9);
}

TEST_F(NearestIk, UnreachableTargetSaysWhy) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(1.2, 0.3, 0.9);
  const auto r = solve_ik_nearest(*model, T, Eigen::VectorXd::Zero(6));
  ASSERT_FALSE(r);
  EXPECT_THAT(r.error().message, HasSubstr("target unreachable: the wrist centre is"));
  EXPECT_THAT(r.error().message, HasSubstr("beyond the arm's reach of 0.8641 m"));
}

TEST_F(NearestIk, EverySolutionOutsideTheLimitsSaysWhichJoint) {
  // Narrow the waist to +-10 deg; a wrist centre at 90 deg azimuth needs theta1 near 90 deg
  // (or near 270 deg on the other shoulder side).
  RobotModel::Description d;
  d.name = "narrow_puma";
  std::vector<JointLimits> limits;
  for (const Joint& j : model->joints()) limits.push_back(j.limits);
  limits[0].lower = radians_from_degrees(-10.0);
  limits[0].upper = radians_from_degrees(10.0);
  d.joints = joints_from_dh(*model->dh(), {"waist", "shoulder", "elbow", "r", "b", "s"}, limits);
  d.dh = model->dh();
  auto narrow = RobotModel::create(d);
  ASSERT_TRUE(narrow) << narrow.error().message;
  Eigen::VectorXd q(6);
  q << kPi / 2, -0.3, 0.2, 0.4, -0.6, 0.1;
  const auto r = solve_ik_nearest(*narrow, tool_pose(*narrow, q), Eigen::VectorXd::Zero(6));
  ASSERT_FALSE(r);
  EXPECT_THAT(r.error().message, HasSubstr("no IK solution within the joint limits: in the "
                                           "nearest one ("));
  EXPECT_THAT(r.error().message, HasSubstr("joint 1 (waist) would be at "));
  EXPECT_THAT(r.error().message, HasSubstr("beyond its upper limit of 10.00 deg"));
}

TEST(NearestIkNumeric, UrdfArmsUseNumericIkSeededAtTheCurrentConfiguration) {
  auto loaded = load_robot(test::data_path("robots/puma560.urdf"));
  ASSERT_TRUE(loaded) << loaded.error().message;
  const RobotModel& model = **loaded;
  std::mt19937_64 rng(33);
  int moves = 0, same = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::VectorXd q_current = test::random_configuration(model, rng);
    Eigen::VectorXd q_target = q_current;
    q_target.array() += 0.02;
    if (!within_limits(model, q_target)) continue;
    const Eigen::Isometry3d T = tool_pose(model, q_target);
    const auto r = solve_ik_nearest(model, T, q_current);
    ASSERT_TRUE(r) << r.error().message;
    ++moves;
    EXPECT_EQ(r->config, "numeric");
    EXPECT_TRUE(r->within_limits);
    EXPECT_TRUE(within_limits(model, r->q));
    const Vector6d e = pose_error_in_base(tool_pose(model, r->q), T);
    EXPECT_LE(e.head<3>().norm(), 1e-6) << "trial " << trial;
    EXPECT_LE(e.tail<3>().norm(), 1e-6) << "trial " << trial;
    // Seeded at q_current, LM lands on the generating configuration except near singular
    // ones (where neighbouring solutions meet).
    same += (r->q - q_target).cwiseAbs().maxCoeff() < 1e-6;
  }
  EXPECT_GT(moves, 150);
  EXPECT_GE(same, moves * 95 / 100) << same << " of " << moves;
  Eigen::Isometry3d far = Eigen::Isometry3d::Identity();
  far.translation() = Eigen::Vector3d(3.0, 0.0, 0.0);
  const auto r = solve_ik_nearest(model, far, Eigen::VectorXd::Zero(6));
  ASSERT_FALSE(r);
  EXPECT_THAT(r.error().message,
              HasSubstr("target unreachable (numeric IK): no configuration within the joint "
                        "limits reaches it after 201 attempts ("));
}

TEST(NearestIkNumeric, SingularNumericSolutionIsFlagged) {
  auto loaded = load_robot(test::data_path("robots/puma560.urdf"));
  ASSERT_TRUE(loaded);
  const RobotModel& model = **loaded;
  Eigen::VectorXd q(6);
  q << 0.2, -0.4, 0.3, 0.0, 0.0, 0.0;  // wrist aligned
  const auto r = solve_ik_nearest(model, tool_pose(model, q), q);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(r->singular);
}

}  // namespace
}  // namespace telear::core
