// `telear robot acm` end to end: it prints the block the shipped robot file stores (so the
// stored matrix is what sampling finds), -o writes the same block, and bad input is one line
// on stderr with exit code 2.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "cli_runner.hpp"
#include "test_util/temp_dir.hpp"

namespace telear {
namespace {

using test::run_telear;
using test::slurp;
using ::testing::HasSubstr;
using ::testing::StartsWith;

const std::string kRobots = std::string(TELEAR_TEST_DATA_DIR) + "/robots";

TEST(RobotAcmCli, PrintsTheBlockTheShippedRobotFileStores) {
  for (const std::string robot : {"ur6", "arm7"}) {
    const auto r = run_telear("robot acm --robot " + robot);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_THAT(r.out, StartsWith("# The allowed-collision matrix of " + robot));
    EXPECT_THAT(r.out, HasSubstr("\nallowed_collisions:\n  - ["));
    EXPECT_THAT(slurp(kRobots + "/" + robot + ".yaml"), HasSubstr(r.out)) << robot;
  }
}

TEST(RobotAcmCli, WritesTheSameBlockToAFile) {
  test_files::TempDir tmp("robot_acm");
  const std::string file = tmp.file("acm.yaml");
  const auto printed = run_telear("robot acm --robot ur6 --samples 100 --seed 4 --never");
  ASSERT_EQ(printed.exit_code, 0) << printed.err;
  EXPECT_THAT(printed.out,
              HasSubstr("# 100 random configurations within the joint limits (seed 4), gripper at "
                        "0.5, constant-distance pairs (within 0.1 mm) allowed, never-in-contact "
                        "pairs allowed."));
  EXPECT_THAT(printed.out, HasSubstr(", never]\n"));
  const auto written =
      run_telear("robot acm --robot ur6 --samples 100 --seed 4 --never -o " + file);
  ASSERT_EQ(written.exit_code, 0) << written.err;
  EXPECT_THAT(written.out, StartsWith("wrote "));
  EXPECT_THAT(written.out, HasSubstr(" allowed pairs of ur6 to " + file + "\n"));
  EXPECT_EQ(slurp(file), printed.out);
}

// Pairs at a constant distance are allowed unless --no-constant (the comment says which);
// --constant-tolerance is that distance range in metres.
TEST(RobotAcmCli, ConstantDistancePairsCanBeLeftChecked) {
  const auto off = run_telear("robot acm --robot puma560 --samples 50 --no-constant");
  ASSERT_EQ(off.exit_code, 0) << off.err;
  EXPECT_THAT(off.out, HasSubstr("(seed 13), gripper at 0.5.\nallowed_collisions:\n"));
  const auto wide = run_telear("robot acm --robot puma560 --samples 50 --constant-tolerance 0.002");
  ASSERT_EQ(wide.exit_code, 0) << wide.err;
  EXPECT_THAT(wide.out, HasSubstr("constant-distance pairs (within 2 mm) allowed."));
}

TEST(RobotAcmCli, ADhTableIsPrintedWithANote) {
  const auto r = run_telear("robot acm --robot puma560 --samples 200");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("  - [link0, link1, adjacent]\n"));
  EXPECT_EQ(r.err,
            "telear robot acm: note: puma560 is a DH table; only a URDF robot file stores "
            "allowed_collisions:\n");
}

TEST(RobotAcmCli, BadInputIsOneLineAndExitCode2) {
  struct Case {
    std::string arguments, message;
  };
  for (const Case& c : std::vector<Case>{
           {"robot acm --robot nosuch_robot", "telear robot acm: "},
           {"robot acm --robot ur6 --samples 0",
            "telear robot acm: --samples: Value 0 not in range"},
           {"robot acm --robot ur6 --constant-tolerance 1",
            "telear robot acm: --constant-tolerance: Value 1 not in range"},
           {"robot acm --robot ur6 -o /nonexistent/dir/acm.yaml",
            "telear robot acm: cannot write '/nonexistent/dir/acm.yaml'"},
           {"robot", "telear robot: "},
       }) {
    const auto r = run_telear(c.arguments);
    EXPECT_EQ(r.exit_code, 2) << c.arguments;
    EXPECT_THAT(r.err, StartsWith(c.message)) << c.arguments;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

}  // namespace
}  // namespace telear
