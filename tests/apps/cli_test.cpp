// End-to-end tests of the `telear` command line: the binary is run as a user would run it.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include "cli_runner.hpp"
#include "telear/core/angles.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/pose.hpp"
#include "telear/core/version.hpp"
#include "test_util/temp_dir.hpp"
#include "test_util/test_util.hpp"

namespace telear {
namespace {

using test::run_telear;
using ::testing::HasSubstr;
using ::testing::Not;

TEST(CliKin, InfoListsJointsLimitsAndNamedConfigurations) {
  const auto r = run_telear("kin info --robot puma560");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("puma560: 6 joints"));
  EXPECT_THAT(r.out, HasSubstr("-160.0 ..  160.0 deg"));
  EXPECT_THAT(r.out, HasSubstr("qn    [0, 45, 180, 0, 45, 0]  (outside limits: joint 3)"));
}

TEST(CliKin, FkJsonMatchesTheModel) {
  const auto r = run_telear("kin fk --robot puma560 --q 0,45,-60,10,20,30 --deg --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto model = test::puma560();
  Eigen::VectorXd q(6);
  q << 0, 45, -60, 10, 20, 30;
  q = q.unaryExpr([](double d) { return core::radians_from_degrees(d); });
  const Eigen::Matrix4d expected = test::dh_product(*model->dh(), q);
  ASSERT_EQ(j["T_base_tool"].size(), 4u);
  for (int r_ = 0; r_ < 4; ++r_) {
    for (int c = 0; c < 4; ++c) {
      EXPECT_NEAR(j["T_base_tool"][r_][c].get<double>(), expected(r_, c), 1e-12);
    }
  }
  EXPECT_EQ(j["frames"].size(), 7u);  // base + one per link
  EXPECT_TRUE(j["within_limits"].get<bool>());
}

TEST(CliKin, FkAcceptsANamedConfiguration) {
  const auto r = run_telear("kin fk --robot puma560 --q qz");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("xyz = (0.4521, -0.1500, 1.1036) m"));
}

TEST(CliKin, BadInputGetsOneClearLineAndNonZeroExit) {
  struct Case {
    std::string args;
    std::string message;
  };
  const Case cases[] = {
      {"kin fk --robot puma999 --q 0,0,0,0,0,0", "telear kin fk: unknown robot 'puma999': no "},
      {"kin fk --robot puma560 --q 0,0,0",
       "telear kin fk: --q: expected 6 numbers, got 3 "
       "(robot 'puma560' has 6 joints)"},
      {"kin fk --robot puma560 --q 0,0,nan,0,0,0",
       "telear kin fk: --q: item 3 ('nan') is not a finite number"},
      {"kin fk --robot puma560 --q 0,0,x,0,0,0",
       "telear kin fk: --q: item 3 ('x') is not a number"},
      {"kin fk --robot /nonexistent.urdf --q 0", "robot file '/nonexistent.urdf' does not exist"},
  };
  for (const Case& c : cases) {
    const auto r = run_telear(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args;
    EXPECT_THAT(r.err, HasSubstr(c.message)) << c.args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
}

TEST(CliKin, MalformedRobotFileIsReported) {
  test_files::TempDir tmp("cli_kin");
  const std::string path = tmp.write("malformed_robot.yaml",
                                     "name: broken\nconvention: standard_dh\njoints: [{d_m: [1,2]");
  const auto r = run_telear("kin info --robot " + path);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("not valid YAML"));
}

TEST(CliKin, MissingSubcommandOrOptionIsAUsageError) {
  EXPECT_NE(run_telear("").exit_code, 0);
  const auto r = run_telear("kin fk --robot puma560");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.err, HasSubstr("--q is required"));
}

// [SECTION] conventions (docs/cli.md): a usage error is one line on stderr and exit 2

TEST(CliConventions, UsageErrorsAreOneLineNamingTheProblemAndExitTwo) {
  struct Case {
    std::string args;
    std::string err;
  };
  const Case cases[] = {
      {"bogus", "telear: unknown subcommand 'bogus' (telear --help lists them)\n"},
      {"kin bogus", "telear kin: unknown subcommand 'bogus' (telear kin --help lists them)\n"},
      {"", "telear: a subcommand is required (telear --help lists them)\n"},
      {"kin info --bogus",
       "telear kin info: unknown option '--bogus' (telear kin info --help lists the options)\n"},
      {"kin info --robot", "telear kin info: --robot needs a value\n"},
      {"kin fk --robot puma560", "telear kin fk: --q is required\n"},
      {"sim capture --views x -o /tmp/x",
       "telear sim capture: --views: 'x' is not a valid value (see --help)\n"},
      {"demo --resolution 20x10",
       "telear demo: --resolution: '20x10' is outside 64x48 .. 1920x1080\n"},
      {"console --resolution 640*480",
       "telear console: --resolution: '640*480' is not WIDTHxHEIGHT (e.g. 640x480)\n"},
      {"console --size 1600x10",
       "telear console: --size: '1600x10' is outside 64x48 .. 8192x8192\n"},
      {"console --robot 127.0.0.1:1",
       "telear console: give both --robot and --vision, or neither (the embedded simulated "
       "servers)\n"},
      {"console --fullscreen-eyes three",
       "telear console: --fullscreen-eyes 'three': two-windows or sbs\n"},
      {"console --headless --fullscreen-eyes sbs",
       "telear console: --fullscreen-eyes needs a display; it cannot be combined with "
       "--headless\n"},
      {"vision-server --resolution 8x8",
       "telear vision-server: --resolution: '8x8' is outside 16x16 .. 8192x8192\n"},
      {"bench stream --resolutions 640x480,big",
       "telear bench stream: --resolutions: 'big' is not WIDTHxHEIGHT (e.g. 640x480)\n"},
  };
  for (const Case& c : cases) {
    const auto r = run_telear(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args;
    EXPECT_EQ(r.err, c.err) << c.args;
    EXPECT_TRUE(r.out.empty()) << c.args << "\n" << r.out;
  }
}

TEST(CliConventions, HelpAndVersionGoToStdoutAndExitZero) {
  auto r = run_telear("--help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.out, HasSubstr("vision-server"));
  EXPECT_TRUE(r.err.empty()) << r.err;
  r = run_telear("kin fk --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.out, HasSubstr("--q"));
  r = run_telear("console --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.out, HasSubstr("--size"));
  r = run_telear("--version");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.out, HasSubstr("telear "));
}

// [SECTION] kin ik

// "a,b,...": the 16 entries of T row-major, at full precision.
std::string row_major_text(const Eigen::Isometry3d& T, const char* separator) {
  std::string text;
  char buffer[40];
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) {
      std::snprintf(buffer, sizeof buffer, "%.17g", T.matrix()(r, c));
      text += (text.empty() ? "" : separator) + std::string(buffer);
    }
  }
  return text;
}

Eigen::VectorXd json_vector(const nlohmann::json& j) {
  Eigen::VectorXd v(static_cast<Eigen::Index>(j.size()));
  for (size_t i = 0; i < j.size(); ++i) v[static_cast<Eigen::Index>(i)] = j[i].get<double>();
  return v;
}

TEST(Cli, VersionIsTheProjectVersionAndTheGitDescription) {
  const auto r = run_telear("--version");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "telear " + std::string(core::version_string()) + "\n");
  EXPECT_THAT(std::string(core::version_string()), ::testing::StartsWith(core::version()));
}

TEST(CliKinIk, JsonGivesAllEightSolutionsReproducingThePose) {
  const auto model = test::puma560();
  Eigen::VectorXd q(6);
  q << 0.3, -0.5, 0.4, 1.0, -0.7, 0.2;
  const Eigen::Isometry3d T = core::tool_pose(*model, q);
  const auto r = run_telear("kin ik --robot puma560 --T " + row_major_text(T, ",") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["method"], "analytic");
  EXPECT_EQ(j["status"], "ok");
  ASSERT_EQ(j["solutions"].size(), 8u);
  const char* configs[] = {"lun", "luf", "ldn", "ldf", "run", "ruf", "rdn", "rdf"};
  bool contains = false;
  for (size_t i = 0; i < 8; ++i) {
    const auto& s = j["solutions"][i];
    EXPECT_EQ(s["config"], configs[i]);
    ASSERT_TRUE(s["within_limits"].is_boolean());
    const Eigen::VectorXd qi = json_vector(s["q"]);
    ASSERT_EQ(qi.size(), 6);
    EXPECT_LT(test::max_abs_diff(core::tool_pose(*model, qi).matrix(), T.matrix()), 1e-9)
        << configs[i];
    contains = contains || (qi - q).cwiseAbs().maxCoeff() < 1e-9;
  }
  EXPECT_TRUE(contains);
}

TEST(CliKinIk, PoseInDegreesWithAConfiguration) {
  const auto model = test::puma560();
  const auto r = run_telear("kin ik --pose 0.5,0.1,0.4,10,80,-20 --deg --config lun --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["units"], "deg");
  ASSERT_EQ(j["solutions"].size(), 1u);
  EXPECT_EQ(j["solutions"][0]["config"], "lun");
  const Eigen::VectorXd q_deg = json_vector(j["solutions"][0]["q"]);
  const Eigen::Isometry3d expected =
      core::pose_from_xyz_rpy({0.5, 0.1, 0.4}, Eigen::Vector3d(core::radians_from_degrees(10),
                                                               core::radians_from_degrees(80),
                                                               core::radians_from_degrees(-20)));
  EXPECT_LT(test::max_abs_diff(core::tool_pose(*model, q_deg.unaryExpr([](double d) {
                                 return core::radians_from_degrees(d);
                               })).matrix(),
                               expected.matrix()),
            1e-9);
}

TEST(CliKinIk, HumanReadableOutputWithBlankSeparatedMatrix) {
  const auto model = test::puma560();
  const Eigen::Isometry3d T = core::tool_pose(*model, *model->named_configuration("qn"));
  const auto r = run_telear("kin ik --T \"" + row_major_text(T, " ") + "\" --config ru --deg");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("puma560: 2 solutions (closed form) for\n"));
  EXPECT_THAT(r.out, HasSubstr("joint values in deg:\n"));
  // qn itself is the 'ruf' solution; q3 = 180 deg lies beyond the elbow's limit.
  EXPECT_THAT(r.out, HasSubstr("  ruf     [   0.0000,   45.0000,  180.0000,"));
  EXPECT_THAT(r.out, HasSubstr("outside limits (joint 3)"));
  EXPECT_TRUE(r.err.empty()) << r.err;
}

TEST(CliKinIk, SingularTargetIsReportedWithTheSolutions) {
  const auto r = run_telear("kin ik --robot puma560 --pose 0.4521,-0.15005,1.10363,0,0,0");
  ASSERT_EQ(r.exit_code, 0) << r.err;  // qz: joints 4 and 6 aligned
  EXPECT_THAT(r.out, HasSubstr("8 solutions"));
  EXPECT_THAT(r.out, HasSubstr("note: wrist singularity"));
  const auto j = nlohmann::json::parse(
      run_telear("kin ik --robot puma560 --pose 0.4521,-0.15005,1.10363,0,0,0 --json").out);
  EXPECT_EQ(j["status"], "singular");
  EXPECT_THAT(j["message"].get<std::string>(), HasSubstr("wrist singularity"));
}

// A 6-DOF URDF arm lists every solution branch found by seeded restarts (core/ik_branches):
// the PUMA's URDF, without its closed form, has the PUMA's eight.
TEST(CliKinIk, UrdfRobotsUseNumericIk) {
  auto model = test::puma560();
  const std::string urdf = test::data_path("robots/puma560.urdf");
  const auto r = run_telear("kin ik --robot " + urdf + " --pose 0.5,0.1,0.4,0,1.5,0 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["method"], "numeric");
  ASSERT_EQ(j["solutions"].size(), 8u);
  const Eigen::Isometry3d expected = core::pose_from_xyz_rpy({0.5, 0.1, 0.4}, {0, 1.5, 0});
  for (std::size_t i = 0; i < 8; ++i) {
    // Appended, not "b" + to_string(i): GCC 12's -Wrestrict false positive (PR 105329).
    std::string label = "b";
    label += std::to_string(i);
    EXPECT_EQ(j["solutions"][i]["config"], label);
    const Eigen::VectorXd q = json_vector(j["solutions"][i]["q"]);
    EXPECT_LT(test::max_abs_diff(core::tool_pose(*model, q).matrix(), expected.matrix()), 1e-6);
  }
}

TEST(CliKinIk, BadInputGetsOneClearLineAndNonZeroExit) {
  struct Case {
    std::string args;
    int exit_code;
    std::string message;
  };
  const std::string urdf = test::data_path("robots/puma560.urdf");
  const Case cases[] = {
      {"kin ik --T 1,0,0,0.5,0,1,0,0.1,0,0,1,0.4,0,0,0", 2,
       "telear kin ik: --T: expected 16 numbers, got 15"},
      {"kin ik --T \"1 0 0 0.5 0 1 0 0.1 0 0 1 0.4 0 0 0 1 7\"", 2,
       "telear kin ik: --T: expected 16 numbers, got 17"},
      {"kin ik --pose 0.5,0.1", 2,
       "telear kin ik: --pose: expected 6 numbers, got 2 (x,y,z in m, roll,pitch,yaw in rad)"},
      {"kin ik --pose 0.5,0.1,nan,0,0,0 --deg", 2,
       "telear kin ik: --pose: item 3 ('nan') is not a finite number (x,y,z in m, "
       "roll,pitch,yaw in deg)"},
      {"kin ik --T 1,0,0,0.5,0,2,0,0.1,0,0,1,0.4,0,0,0,1", 2,
       "telear kin ik: --T is not a rigid transform: its rotation block is not orthonormal "
       "(R R^T - I is off by 3; tolerance 0.0001)"},
      {"kin ik --T 1,0,0,0.5,0,1,0,0.1,0,0,-1,0.4,0,0,0,1", 2,
       "telear kin ik: --T is not a rigid transform: its rotation block is a reflection"},
      {"kin ik --T 1,0,0,0.5,0,1,0,0.1,0,0,1,0.4,0,0,1,1", 2,
       "telear kin ik: --T is not a rigid transform: its last row is not 0 0 0 1"},
      {"kin ik --pose 0.5,0,0.3,0,0,0 --T 1", 2,
       "telear kin ik: give the target as --T or as --pose, not both"},
      {"kin ik --robot puma560", 2,
       "telear kin ik: needs a target: --T \"16 numbers, row-major\" or --pose "
       "x,y,z,roll,pitch,yaw"},
      {"kin ik --pose 0.5,0,0.3,0,0,0 --config lx", 2,
       "telear kin ik: --config: configuration 'lx': unknown letter 'x'"},
      {"kin ik --pose 0.5,0,0.3,0,0,0 --config lr", 2,
       "telear kin ik: --config: configuration 'lr': more than one of l/r, u/d or n/f"},
      {"kin ik --pose 2,0,0.3,0,0,0", 1,
       "telear kin ik: target unreachable: the wrist centre is 2.0287 m from the shoulder, "
       "beyond the arm's reach of 0.8641 m"},
      {"kin ik --pose 0.05,0,1,0,0,0", 1,
       "telear kin ik: target unreachable: the wrist centre is 0.0500 m from joint 1's axis, "
       "inside the shoulder-offset cylinder of radius 0.1500 m"},
      {"kin ik --robot " + urdf + " --pose 0.5,0,0.3,0,0,0 --config lun", 2,
       "telear kin ik: --config selects closed-form solutions, and robot 'puma560' has no "
       "standard DH table"},
      {"kin ik --robot " + urdf + " --pose 2,0,0.3,0,0,0", 1,
       "telear kin ik: solve_ik_all: target unreachable: none of 96 seeded attempts converged"},
      {"kin ik --robot puma999 --pose 0.5,0,0.3,0,0,0", 2,
       "telear kin ik: unknown robot 'puma999'"},
  };
  for (const Case& c : cases) {
    const auto r = run_telear(c.args);
    EXPECT_EQ(r.exit_code, c.exit_code) << c.args;
    EXPECT_THAT(r.err, HasSubstr(c.message)) << c.args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(r.out.empty()) << c.args << "\n" << r.out;
  }
}

TEST(CliKin, DemoRunsInverseKinematicsBackFromEachNamedConfiguration) {
  const auto r = run_telear("kin demo --robot puma560");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("closed-form IK, 8 solutions (deg):"));
  EXPECT_THAT(r.out, HasSubstr("    ruf  [    0.00,    45.00,   180.00,"));
  EXPECT_THAT(r.out, HasSubstr("qn is solution ruf"));
  EXPECT_THAT(r.out, HasSubstr("qz is solution "));
  EXPECT_THAT(r.out, Not(HasSubstr("none of them")));
  EXPECT_THAT(r.out, HasSubstr("worst round trip |FK(IK(T)) - T| = "));
}

// `telear bench kin`'s table: row name -> its cells "operation | telear | KDL | KDL/telear |
// target | met".
std::map<std::string, std::vector<std::string>> bench_table(const std::string& out) {
  std::map<std::string, std::vector<std::string>> rows;
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);) {
    std::vector<std::string> cells;
    std::istringstream fields(line);
    for (std::string cell; std::getline(fields, cell, '|');) {
      const auto first = cell.find_first_not_of(' ');
      const auto last = cell.find_last_not_of(' ');
      cells.push_back(first == std::string::npos ? "" : cell.substr(first, last - first + 1));
    }
    if (cells.size() >= 5) rows[cells[0]] = cells;
  }
  return rows;
}

TEST(CliBench, KinPrintsEveryRowWithKdlRatiosAndTheBaselineAgrees) {
  const auto r = run_telear("bench kin --poses 200");
  if (r.exit_code == 2 && r.err.find("not built") != std::string::npos) GTEST_SKIP() << r.err;
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto rows = bench_table(r.out);
  const char* with_ratio[] = {"FK, all frames",
                              "FK, joint 5 changed (incremental)",
                              "Jacobian (with FK)",
                              "numeric IK, cold start, q = 0: mean",
                              "numeric IK, cold start, q = 0: p99",
                              "numeric IK, seeded near the answer: mean",
                              "numeric IK, seeded near the answer: p99"};
  for (const char* name : with_ratio) {
    ASSERT_TRUE(rows.count(name)) << name << "\n" << r.out;
    EXPECT_THAT(rows[name][1], ::testing::EndsWith("s")) << name;  // ns or us
    EXPECT_THAT(rows[name][2], ::testing::EndsWith("s")) << name;
    EXPECT_THAT(rows[name][3], ::testing::MatchesRegex("[0-9.]+x")) << name;
  }
  for (const char* name :
       {"analytic IK, all 8 (solve_puma_ik)", "analytic IK, all 8 (labelled API)"}) {
    ASSERT_TRUE(rows.count(name)) << name;
    EXPECT_EQ(rows[name][2], "-") << name;  // KDL has no closed form
  }
  EXPECT_EQ(rows["numeric IK, cold start, q = 0: solved"][4], ">= 99.9 %");
  EXPECT_THAT(rows["FK, all frames"][4], HasSubstr(">= 10x KDL"));
  // The baseline is the same chain: KDL's frames equal telear's.
  const std::string check =
      "check: KDL FK vs telear FK, all 6 frames of 200 configurations: "
      "max |difference| ";
  const auto at = r.out.find(check);
  ASSERT_NE(at, std::string::npos) << r.out;
  EXPECT_LT(std::stod(r.out.substr(at + check.size())), 1e-12);

  const auto bad = run_telear("bench kin --poses 5");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(bad.err, "telear bench kin: --poses must be at least 100, got 5\n");
}

// A URDF arm (issue 12): the KDL chain comes from kdl_parser, the IK rows from telear's numeric
// solvers (no closed form), each beside KDL's LMA; a tree with several leaves needs --tip.
TEST(CliBench, KinTakesAnyUrdfArmWithTheRobotOptions) {
  const auto r = run_telear("bench kin --robot ur6 --poses 100");
  if (r.exit_code == 2 && r.err.find("not built") != std::string::npos) GTEST_SKIP() << r.err;
  if (r.exit_code == 2 && r.err.find("kdl_parser") != std::string::npos) GTEST_SKIP() << r.err;
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("robot ur6 (6 joints, URDF tip "));
  auto rows = bench_table(r.out);
  ASSERT_TRUE(rows.count("operation")) << r.out;
  EXPECT_EQ(rows["operation"][1], "telear");
  EXPECT_EQ(rows["operation"][2], "KDL");
  for (const char* name :
       {"FK, all frames", "Jacobian (with FK)", "numeric IK, cold start, q = 0: mean",
        "numeric IK, seeded near the answer: mean"}) {
    ASSERT_TRUE(rows.count(name)) << name << "\n" << r.out;
    EXPECT_THAT(rows[name][1], ::testing::EndsWith("s")) << name;  // telear: ns or us
    EXPECT_THAT(rows[name][2], ::testing::EndsWith("s")) << name;  // KDL
    EXPECT_THAT(rows[name][3], ::testing::MatchesRegex("[0-9.]+x")) << name;
  }
  EXPECT_THAT(rows["numeric IK, cold start, q = 0: solved"][1], ::testing::EndsWith("%"));
  EXPECT_THAT(rows["numeric IK, cold start, q = 0: solved"][2], ::testing::EndsWith("%"));
  // No closed form for this arm: every branch by seeded LM instead, with no KDL counterpart.
  EXPECT_EQ(rows.count("analytic IK, all 8 (solve_puma_ik)"), 0u);
  const std::string branches = "every branch (solve_ik_all), 100 targets: solved";
  ASSERT_TRUE(rows.count(branches)) << r.out;
  EXPECT_EQ(rows[branches][2], "-");
  // The baseline (kdl_parser's chain of the same URDF) is the same arm.
  const std::string check = "vs telear FK, tool pose of 100 configurations: max |difference| ";
  const auto at = r.out.find(check);
  ASSERT_NE(at, std::string::npos) << r.out;
  EXPECT_LT(std::stod(r.out.substr(at + check.size())), 1e-12);

  const std::string branching = std::string(TELEAR_TEST_FILES_DIR) + "/urdf/branching_tip.urdf";
  const auto no_tip = run_telear("bench kin --poses 100 --robot " + branching);
  EXPECT_EQ(no_tip.exit_code, 2);
  EXPECT_THAT(no_tip.err, HasSubstr("the tree has several leaf links (a, b, tcp); name the tip "
                                    "link"));
  EXPECT_THAT(no_tip.err, ::testing::StartsWith("telear bench kin: "));
  EXPECT_EQ(std::count(no_tip.err.begin(), no_tip.err.end(), '\n'), 1) << no_tip.err;
  const auto with_tip = run_telear("bench kin --poses 100 --robot " + branching + " --tip a");
  ASSERT_EQ(with_tip.exit_code, 0) << with_tip.err;
  EXPECT_THAT(with_tip.out, HasSubstr("robot branching (2 joints, URDF tip a)"));
}

}  // namespace
}  // namespace telear
