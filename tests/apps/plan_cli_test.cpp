// `telear plan check` end to end: a plan that drives the PUMA's forearm into the table is
// refused with the contact named (exit 1), a plan that stays clear passes (exit 0), --json has
// the documented fields, and bad input is one line on stderr with exit code 2.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace telear {
namespace {

using test::run_telear;
using ::testing::HasSubstr;
using ::testing::StartsWith;

class PlanCheckCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        std::filesystem::path(::testing::TempDir()) / ("plan_check_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path) << text;
    return path;
  }

  std::filesystem::path dir_;
};

const std::string kWorkspace = std::string(TELEAR_TEST_DATA_DIR) + "/workspaces/puma560_table.yaml";

// From the zero pose down into the table: the forearm (link3) meets the table top.
const std::string kIntoTheTable = R"(robot: puma560
waypoints:
  - {label: start, q_rad: [0, 0, 0, 0, 0, 0]}
  - {label: down, q_rad: [0.077, -0.392, -2.334, 0.240, 0.745, 1.557]}
)";

// From the zero pose up to the ready pose (arm straight up): clear of everything.
const std::string kUp = R"(robot: puma560
waypoints:
  - {q_rad: [0, 0, 0, 0, 0, 0]}
  - {q_rad: [0, 1.5707963, -1.5707963, 0, 0, 0]}
)";

TEST_F(PlanCheckCli, APlanIntoTheTableIsACollisionNamedInJson) {
  const auto r = run_telear("plan check --robot puma560 --workspace " + kWorkspace + " --plan " +
                            write("down.yaml", kIntoTheTable) + " --json");
  ASSERT_EQ(r.exit_code, 1) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_FALSE(j["collision_free"].get<bool>());
  ASSERT_FALSE(j["collisions"].empty());
  bool table = false;
  for (const auto& c : j["collisions"]) {
    EXPECT_GT(c["time_s"].get<double>(), 0.0);
    EXPECT_LE(c["time_s"].get<double>(), j["duration_s"].get<double>());
    EXPECT_GE(c["depth_m"].get<double>(), 0.0);
    EXPECT_TRUE(c["link"].is_string());
    table = table || (c["object"] == "table_top" && !c["self"].get<bool>());
  }
  EXPECT_TRUE(table) << r.out;
  EXPECT_EQ(j["min_clearance_m"].get<double>(), 0.0);
}

TEST_F(PlanCheckCli, AClearPlanPassesWithItsMinimumClearance) {
  const std::string plan = write("up.yaml", kUp);
  const auto r =
      run_telear("plan check --robot puma560 --workspace " + kWorkspace + " --plan " + plan);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_THAT(r.out, HasSubstr("collision-free"));
  EXPECT_THAT(r.out, HasSubstr("min clearance"));
  const auto j = run_telear("plan check --robot puma560 --workspace " + kWorkspace + " --plan " +
                            plan + " --json");
  ASSERT_EQ(j.exit_code, 0) << j.err;
  const nlohmann::json json = nlohmann::json::parse(j.out);
  EXPECT_TRUE(json["collision_free"].get<bool>());
  EXPECT_TRUE(json["collisions"].empty());
  EXPECT_GT(json["min_clearance_m"].get<double>(), 0.0);
}

TEST_F(PlanCheckCli, BadInputIsOneLineOnStderrAndExitCode2) {
  const std::string plan = write("up.yaml", kUp);
  struct Case {
    std::string arguments, message;
  };
  const std::vector<Case> cases = {
      {"--robot puma560 --workspace " + kWorkspace + " --plan " + (dir_ / "none.yaml").string(),
       "none.yaml"},
      {"--robot nosuch --workspace " + kWorkspace + " --plan " + plan, "unknown robot 'nosuch'"},
      {"--robot puma560 --workspace " +
           write("bad_ws.yaml", "objects:\n  - {name: a, shape: box, size: [1, -2, 1]}\n") +
           " --plan " + plan,
       "object 'a': size[1] must be positive, got -2"},
      {"--robot puma560 --workspace " +
           write("mesh_ws.yaml", "objects:\n  - {name: m, shape: mesh, file: gone.stl}\n") +
           " --plan " + plan,
       "object 'm': file: mesh 'gone.stl' not found"},
      {"--robot ur6 --workspace " + kWorkspace + " --plan " + plan, "puma560"},
      {"--robot puma560 --workspace " + kWorkspace, "--plan"},
  };
  for (const Case& c : cases) {
    const auto r = run_telear("plan check " + c.arguments);
    EXPECT_EQ(r.exit_code, 2) << c.arguments << "\n" << r.out << r.err;
    EXPECT_THAT(r.err, StartsWith("telear plan check: ")) << c.arguments;
    EXPECT_THAT(r.err, HasSubstr(c.message)) << c.arguments;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
}

}  // namespace
}  // namespace telear
