#include "telear/core/ik_analytic.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "telear/core/angles.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/robot_loader.hpp"
#include "test_util/test_util.hpp"

namespace telear::core {
namespace {

using test::dh_product;
using test::kPi;
using test::max_abs_diff;
using ::testing::HasSubstr;

// Largest |wrap(a_i - b_i)|: joint vectors equal modulo 2 pi.
double max_angle_diff(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  double worst = 0.0;
  for (Eigen::Index i = 0; i < a.size(); ++i) {
    worst = std::max(worst, std::abs(wrap_to_pi(a[i] - b[i])));
  }
  return worst;
}

// A 6-joint standard-DH model from rows, with generous limits and an optional tool.
RobotModel dh_model(const std::vector<DhRow>& rows,
                    const Eigen::Isometry3d& T_flange_tool = Eigen::Isometry3d::Identity(),
                    double limit = kPi) {
  RobotModel::Description d;
  d.name = "test_arm";
  std::vector<JointLimits> limits(rows.size(), JointLimits{-limit, limit, 1.0, 1.0});
  d.joints = joints_from_dh(rows, {}, limits);
  d.dh = rows;
  d.T_flange_tool = T_flange_tool;
  auto model = RobotModel::create(std::move(d));
  EXPECT_TRUE(model) << model.error().message;
  return std::move(model).value();
}

// The Toolbox's configuration letters of q, derived from the definitions in ik_analytic.hpp
// by computing the wrist centre in frame 1 directly from q (theta = q for the PUMA):
//   V114 = a2 c2 + a3 c23 - d4 s23 (> 0 on the 'r' branch), Pz = a2 s2 + a3 s23 + d4 c23,
//   theta2 = atan2(Pz, V114) + n2 Psi with Psi in [0, pi]: n2 = sign(theta2 - atan2(...)),
//   'u' when n2 = +1 on 'r' (-1 on 'l'); 'n' when theta5 < 0 (ZYZ without flip, negated).
std::string expected_config(const std::vector<DhRow>& dh, const Eigen::VectorXd& q) {
  const double a2 = dh[1].a, a3 = dh[2].a, d4 = dh[3].d;
  const double v114 = a2 * std::cos(q[1]) + a3 * std::cos(q[1] + q[2]) - d4 * std::sin(q[1] + q[2]);
  const double pz = a2 * std::sin(q[1]) + a3 * std::sin(q[1] + q[2]) + d4 * std::cos(q[1] + q[2]);
  const bool right = v114 > 0.0;
  const double n2 = wrap_to_pi(q[1] - std::atan2(pz, v114)) > 0.0 ? 1.0 : -1.0;
  const bool up = right ? n2 > 0.0 : n2 < 0.0;
  const bool no_flip = wrap_to_pi(q[4]) < 0.0;
  return std::string(right ? "r" : "l") + (up ? "u" : "d") + (no_flip ? "n" : "f");
}

// True when every joint of q has a 2 pi equivalent within the model's limits.
bool equivalents_within_limits(const RobotModel& model, const Eigen::VectorXd& q) {
  for (int j = 0; j < model.dof(); ++j) {
    bool found = false;
    for (int k = -2; k <= 2; ++k) {
      const double v = q[j] + 2.0 * kPi * k;
      found = found || (v >= model.lower_limits()[j] - 1e-9 && v <= model.upper_limits()[j] + 1e-9);
    }
    if (!found) return false;
  }
  return true;
}

class PumaAnalyticIk : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(model);
    auto g = puma_geometry(*model);
    ASSERT_TRUE(g) << g.error().message;
    geometry = *g;
  }
  RobotModelPtr model = test::puma560();
  PumaGeometry geometry;
};

TEST_F(PumaAnalyticIk, GeometryIsThePumas) {
  EXPECT_DOUBLE_EQ(geometry.d1, 0.67183);
  EXPECT_DOUBLE_EQ(geometry.a2, 0.4318);
  EXPECT_DOUBLE_EQ(geometry.a3, 0.0203);
  EXPECT_DOUBLE_EQ(geometry.d4, 0.4318);
  EXPECT_DOUBLE_EQ(geometry.shoulder_offset, 0.15005);
  EXPECT_FALSE(geometry.mirrored);
  EXPECT_NEAR(geometry.max_reach, 0.4318 + std::hypot(0.0203, 0.4318), 1e-15);
}

TEST_F(PumaAnalyticIk, RoundTripsOfAllEightSolutionsOverRandomPoses) {
  std::mt19937_64 rng(20240601);
  KinematicsData data(*model);
  double worst_fk = 0.0;
  int label_checks = 0;
  for (int trial = 0; trial < 10000; ++trial) {
    const Eigen::VectorXd q = test::random_configuration(*model, rng);
    const Eigen::Isometry3d T = tool_pose(*model, q);
    const AnalyticIkResult r = solve_analytic_ik(*model, geometry, T);
    ASSERT_NE(r.status, IkStatus::kUnreachable) << r.message;
    ASSERT_EQ(r.solutions.size(), 8u);
    bool contains_generator = false;
    for (size_t i = 0; i < r.solutions.size(); ++i) {
      const IkSolution& s = r.solutions[i];
      EXPECT_EQ(s.config, PumaIkSolutions::kConfigs[i]);
      ASSERT_TRUE(s.q.allFinite());
      for (int j = 0; j < 6; ++j) {
        EXPECT_GT(s.q[j], -kPi);
        EXPECT_LE(s.q[j], kPi);
      }
      forward_kinematics(*model, data, s.q);
      const double fk_error = max_abs_diff(data.T_base_tool.matrix(), T.matrix());
      worst_fk = std::max(worst_fk, fk_error);
      ASSERT_LT(fk_error, 1e-9) << "trial " << trial << " config " << s.config;
      EXPECT_EQ(s.within_limits, equivalents_within_limits(*model, s.q)) << s.config;
      contains_generator = contains_generator || max_angle_diff(s.q, q) < 1e-8;
    }
    EXPECT_TRUE(contains_generator) << "trial " << trial;
    // The solution labelled as the generating configuration's branch reproduces it.
    const std::string label = expected_config(*model->dh(), q);
    for (const IkSolution& s : r.solutions) {
      if (s.config != label) continue;
      EXPECT_LT(max_angle_diff(s.q, q), 1e-8) << "trial " << trial << " label " << label;
      EXPECT_TRUE(s.within_limits);
      ++label_checks;
    }
  }
  EXPECT_EQ(label_checks, 10000);
  RecordProperty("worst_fk_error", std::to_string(worst_fk));
}

TEST_F(PumaAnalyticIk, ConfigurationFiltersSelectByLetters) {
  const Eigen::Isometry3d T = tool_pose(*model, *model->named_configuration("qn"));
  const auto configs = [&](std::string_view c) {
    std::vector<std::string> out;
    for (const IkSolution& s : solve_analytic_ik(*model, geometry, T, c).solutions) {
      out.push_back(s.config);
    }
    return out;
  };
  using V = std::vector<std::string>;
  EXPECT_EQ(configs("lun"), V{"lun"});
  EXPECT_EQ(configs("rdf"), V{"rdf"});
  EXPECT_EQ(configs("l"), (V{"lun", "luf", "ldn", "ldf"}));
  EXPECT_EQ(configs("un"), (V{"lun", "run"}));
  EXPECT_EQ(configs("fr"), (V{"ruf", "rdf"}));
  EXPECT_EQ(configs("").size(), 8u);
}

TEST(IkConfig, CheckRejectsUnknownAndRepeatedLetters) {
  EXPECT_TRUE(check_ik_config(""));
  EXPECT_TRUE(check_ik_config("lun"));
  EXPECT_TRUE(check_ik_config("fd"));
  EXPECT_EQ(check_ik_config("lux").error().message,
            "configuration 'lux': unknown letter 'x' (use l/r, u/d, n/f, e.g. \"lun\")");
  EXPECT_EQ(check_ik_config("lr").error().message,
            "configuration 'lr': more than one of l/r, u/d or n/f");
  EXPECT_FALSE(check_ik_config("LUN"));
}

TEST_F(PumaAnalyticIk, QnContainsTheToolboxAnswer) {
  // RVC3's README: ikine_LM on fkine(qn) returns this configuration (4 digits).
  Eigen::VectorXd q_toolbox(6);
  q_toolbox << 7.235e-08, -0.8335, 0.09396, 3.142, 0.8312, -3.142;
  const Eigen::VectorXd qn = *model->named_configuration("qn");
  const AnalyticIkResult r = solve_analytic_ik(*model, geometry, tool_pose(*model, qn));
  ASSERT_EQ(r.solutions.size(), 8u);
  bool toolbox = false, named = false;
  for (const IkSolution& s : r.solutions) {
    toolbox = toolbox || max_angle_diff(s.q, q_toolbox) < 1e-3;
    named = named || max_angle_diff(s.q, qn) < 1e-9;
  }
  EXPECT_TRUE(toolbox);
  EXPECT_TRUE(named);
  // qn: theta1 = 0 with the wrist centre in front (V114 > 0): 'r'; the elbow above the
  // shoulder-wrist line (theta2 above atan2(Pz, V114)): 'u'; q5 = +45 deg: 'f'.
  EXPECT_EQ(expected_config(*model->dh(), qn), "ruf");
  EXPECT_LT(
      max_angle_diff(
          solve_analytic_ik(*model, geometry, tool_pose(*model, qn), "ruf").solutions.at(0).q, qn),
      1e-9);
}

// A tool pose whose wrist centre (flange origin for the PUMA) is at p, orientation identity.
Eigen::Isometry3d at(double x, double y, double z) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}

TEST_F(PumaAnalyticIk, UnreachableTargetsSayWhy) {
  const AnalyticIkResult far = solve_analytic_ik(*model, geometry, at(1.5, 0.0, 0.67183));
  EXPECT_EQ(far.status, IkStatus::kUnreachable);
  EXPECT_TRUE(far.solutions.empty());
  EXPECT_EQ(far.message,
            "target unreachable: the wrist centre is 1.4925 m from the shoulder, beyond the "
            "arm's reach of 0.8641 m");

  const AnalyticIkResult cylinder = solve_analytic_ik(*model, geometry, at(0.05, 0.0, 1.0));
  EXPECT_EQ(cylinder.status, IkStatus::kUnreachable);
  EXPECT_TRUE(cylinder.solutions.empty());
  EXPECT_EQ(cylinder.message,
            "target unreachable: the wrist centre is 0.0500 m from joint 1's axis, inside the "
            "shoulder-offset cylinder of radius 0.1500 m");

  // On the cylinder, at shoulder height: the wrist centre would sit in the shoulder.
  const AnalyticIkResult close = solve_analytic_ik(*model, geometry, at(0.0, -0.15005, 0.67183));
  EXPECT_EQ(close.status, IkStatus::kUnreachable);
  EXPECT_THAT(close.message, HasSubstr("closer than the arm's minimum reach of 0.0005 m"));

  Eigen::Isometry3d nan = at(0.5, 0.0, 0.5);
  nan(1, 1) = std::numeric_limits<double>::quiet_NaN();
  const AnalyticIkResult bad = solve_analytic_ik(*model, geometry, nan);
  EXPECT_EQ(bad.status, IkStatus::kUnreachable);
  EXPECT_EQ(bad.message, "target pose is not finite");
}

TEST_F(PumaAnalyticIk, WristSingularityIsFlaggedAndStillExact) {
  for (const double q5 : {0.0, 1e-9}) {
    Eigen::VectorXd q(6);
    q << 0.2, -0.4, 0.3, 0.5, q5, -0.25;
    const Eigen::Isometry3d T = tool_pose(*model, q);
    const AnalyticIkResult r = solve_analytic_ik(*model, geometry, T);
    EXPECT_EQ(r.status, IkStatus::kSingular);
    EXPECT_THAT(r.message, HasSubstr("wrist singularity"));
    ASSERT_EQ(r.solutions.size(), 8u);
    int singular = 0;
    for (const IkSolution& s : r.solutions) {
      ASSERT_TRUE(s.q.allFinite());
      EXPECT_LT(max_abs_diff(tool_pose(*model, s.q).matrix(), T.matrix()), 1e-9) << s.config;
      singular += s.singular;
    }
    // Only the generating arm branch has its wrist aligned; the others have q5 != 0.
    EXPECT_GE(singular, 2);
    const std::string branch = expected_config(*model->dh(), q).substr(0, 2);
    EXPECT_EQ(branch, "rd");
    const IkSolution& same = solve_analytic_ik(*model, geometry, T, branch).solutions.at(0);
    EXPECT_TRUE(same.singular);
    if (q5 == 0.0) {
      // Only q4 + q6 is determined: q4 = 0 as the Toolbox chooses.
      EXPECT_EQ(same.q[3], 0.0);
      EXPECT_NEAR(same.q[5], 0.5 - 0.25, 1e-12);
    }
  }
}

TEST_F(PumaAnalyticIk, ElbowAndShoulderSingularitiesAreFlagged) {
  const double beta = std::atan2(0.4318, 0.0203);
  Eigen::VectorXd stretched(6);
  stretched << 0.1, 0.2, -beta, 0.3, 0.6, 0.1;  // forearm in line with the upper arm
  AnalyticIkResult r = solve_analytic_ik(*model, geometry, tool_pose(*model, stretched));
  EXPECT_EQ(r.status, IkStatus::kSingular);
  EXPECT_THAT(r.message, HasSubstr("elbow singularity"));
  for (const IkSolution& s : r.solutions) {
    EXPECT_TRUE(s.singular);
    EXPECT_LT(max_abs_diff(tool_pose(*model, s.q).matrix(), tool_pose(*model, stretched).matrix()),
              1e-9);
  }

  Eigen::VectorXd over(6);  // wrist centre straight above the shoulder: V114 = 0
  over << 0.1, kPi / 2, std::atan2(0.0203, 0.4318) - kPi / 2, 0.3, 0.6, 0.1;
  r = solve_analytic_ik(*model, geometry, tool_pose(*model, over));
  EXPECT_EQ(r.status, IkStatus::kSingular);
  EXPECT_THAT(r.message, HasSubstr("shoulder singularity"));
  for (const IkSolution& s : r.solutions) {
    EXPECT_TRUE(s.singular);
    EXPECT_LT(max_abs_diff(tool_pose(*model, s.q).matrix(), tool_pose(*model, over).matrix()),
              1e-9);
  }
}

TEST_F(PumaAnalyticIk, NamedConfigurationsAreRecovered) {
  for (const NamedConfiguration& c : model->named_configurations()) {
    const AnalyticIkResult r = solve_analytic_ik(*model, geometry, tool_pose(*model, c.q));
    ASSERT_EQ(r.solutions.size(), 8u) << c.name << ": " << r.message;
    bool found = false;
    for (const IkSolution& s : r.solutions) {
      EXPECT_LT(max_abs_diff(tool_pose(*model, s.q).matrix(), tool_pose(*model, c.q).matrix()),
                1e-9);
      // qz and qr are wrist-singular: q4 + q6 is what is recovered.
      Eigen::VectorXd folded = s.q;
      if (s.singular) {
        folded[5] += folded[3];
        folded[3] = 0.0;
      }
      Eigen::VectorXd target = c.q;
      if (s.singular) {
        target[5] += target[3];
        target[3] = 0.0;
      }
      found = found || max_angle_diff(folded, target) < 1e-9;
    }
    EXPECT_TRUE(found) << c.name;
  }
}

TEST_F(PumaAnalyticIk, AllocationFreeCoreAgreesWithTheApi) {
  std::mt19937_64 rng(7);
  PumaIkSolutions raw;
  for (int trial = 0; trial < 100; ++trial) {
    const Eigen::Isometry3d T = tool_pose(*model, test::random_configuration(*model, rng));
    solve_puma_ik(geometry, T, raw);
    ASSERT_TRUE(raw.reachable());
    const AnalyticIkResult r = solve_analytic_ik(*model, geometry, T);
    for (int i = 0; i < 8; ++i) {
      EXPECT_EQ(r.solutions[static_cast<size_t>(i)].q, raw.q[static_cast<size_t>(i)]);
    }
  }
}

// [SECTION] The geometry class beyond the PUMA

struct ClassCase {
  const char* name;
  std::vector<DhRow> rows;
  Eigen::Isometry3d tool;
};

std::vector<ClassCase> class_cases() {
  const double h = kPi / 2;
  Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();
  tool.translate(Eigen::Vector3d(0.01, -0.02, 0.15)).rotate(rotation_from_rpy(0.3, -0.2, 0.9));
  return {
      // Offsets, d2 and d3 both non-zero, a negative a3, and a last row with d6, a6, alpha6.
      {"offsets_and_last_row",
       {{0.5, 0, h, 0.1},
        {0.05, 0.6, 0, -0.4},
        {0.1, -0.03, -h, 0.25},
        {0.55, 0, h, 0.7},
        {0, 0, -h, -0.3},
        {0.08, 0.02, 0.4, 1.1}},
       tool},
      // Mirrored alpha signs (every alpha of joints 1..5 negated).
      {"mirrored",
       {{0.67183, 0, -h, 0},
        {0, 0.4318, 0, 0},
        {0.15005, 0.0203, h, 0},
        {0.4318, 0, -h, 0},
        {0, 0, h, 0},
        {0.05, 0, 0, 0}},
       tool},
      // No shoulder offset, negative a2 and d1, elbow offset larger than the forearm.
      {"negative_lengths",
       {{-0.3, 0, h, 0.2},
        {0, -0.5, 0, 0},
        {0, 0.4, -h, -0.5},
        {0.1, 0, h, 0},
        {0, 0, -h, 0},
        {0, 0, 0, 0.3}},
       Eigen::Isometry3d::Identity()},
  };
}

TEST(AnalyticIkClass, RoundTripsForOtherArmsOfTheClass) {
  for (const ClassCase& c : class_cases()) {
    SCOPED_TRACE(c.name);
    const RobotModel model = dh_model(c.rows, c.tool);
    auto g = puma_geometry(model);
    ASSERT_TRUE(g) << g.error().message;
    EXPECT_EQ(g->mirrored, std::string(c.name) == "mirrored");
    std::mt19937_64 rng(99);
    for (int trial = 0; trial < 2000; ++trial) {
      const Eigen::VectorXd q = test::random_configuration(model, rng);
      const Eigen::Isometry3d T = tool_pose(model, q);
      ASSERT_LT(max_abs_diff(T.matrix(), dh_product(c.rows, q) * c.tool.matrix()), 1e-12);
      const AnalyticIkResult r = solve_analytic_ik(model, *g, T);
      ASSERT_EQ(r.solutions.size(), 8u) << r.message;
      bool contains = false;
      for (const IkSolution& s : r.solutions) {
        ASSERT_LT(max_abs_diff(tool_pose(model, s.q).matrix(), T.matrix()), 1e-9)
            << "trial " << trial << " " << s.config;
        contains = contains || max_angle_diff(s.q, q) < 1e-8;
      }
      EXPECT_TRUE(contains) << "trial " << trial;
    }
  }
}

TEST(AnalyticIkClass, RejectsArmsOutsideTheClassWithTheParameter) {
  const auto puma = test::puma560();
  ASSERT_TRUE(puma);
  const std::vector<DhRow> rows = *puma->dh();
  const auto message = [](const RobotModel& m) { return puma_geometry(m).error().message; };

  std::vector<DhRow> r = rows;
  r[1].alpha = radians_from_degrees(10.0);
  EXPECT_EQ(message(dh_model(r)),
            "robot 'test_arm' is not of the PUMA class (closed-form IK): joint 2 has alpha = "
            "10.00 deg, needs 0.00 deg (alpha pattern +90, 0, -90, +90, -90 deg, or all negated)");
  r = rows;
  r[3].alpha = -kPi / 2;  // half mirrored
  EXPECT_THAT(message(dh_model(r)), HasSubstr("joint 4 has alpha = -90.00 deg, needs 90.00 deg"));
  r = rows;
  r[3].a = 0.01;
  EXPECT_EQ(message(dh_model(r)),
            "robot 'test_arm' is not of the PUMA class (closed-form IK): joint 4 has a = 0.0100 m, "
            "needs 0");
  r = rows;
  r[4].d = 0.05;
  EXPECT_THAT(message(dh_model(r)), HasSubstr("joint 5 has d = 0.0500 m, needs 0"));
  r = rows;
  r[0].a = 0.1;
  EXPECT_THAT(message(dh_model(r)), HasSubstr("joint 1 has a = 0.1000 m, needs 0"));
  r = rows;
  r[1].a = 0.0;
  EXPECT_THAT(message(dh_model(r)), HasSubstr("joint 2 has a = 0 (no upper arm)"));

  auto urdf = load_robot(test::data_path("robots/puma560.urdf"));
  ASSERT_TRUE(urdf) << urdf.error().message;
  EXPECT_EQ(puma_geometry(**urdf).error().message,
            "robot 'puma560' has no standard DH table (the PUMA class's closed form reads one; "
            "a URDF arm has the UR class's, ik_ur.hpp, or numeric IK)");

  std::vector<DhRow> five(rows.begin(), rows.end() - 1);
  EXPECT_THAT(message(dh_model(five)), HasSubstr("it has 5 joints, needs 6"));
}

}  // namespace
}  // namespace telear::core
