// End-to-end tests of the `telear` command line: the binary is run as a user would run it.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "core/kinematics.hpp"
#include "test_util/test_util.hpp"

namespace telear {
namespace {

using test::run_telear;
using ::testing::HasSubstr;

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
  q *= M_PI / 180.0;
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
  const std::string path = ::testing::TempDir() + "malformed_robot.yaml";
  std::ofstream(path) << "name: broken\nconvention: standard_dh\njoints: [{d_m: [1,2]";
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

}  // namespace
}  // namespace telear
