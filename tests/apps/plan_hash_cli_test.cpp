// Determinism across processes (issue 14): a plan hashed by `telear plan hash` in another OS
// process gives the 64 hex digits this process computes with core::plan_hash from the same
// numbers, and a change of one joint value by 1e-9 rad changes the other process's hash.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "telear/core/plan_hash.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/core/trajectory.hpp"
#include "test_util/temp_dir.hpp"

namespace telear {
namespace {

using test::run_telear;
using ::testing::StartsWith;

// Four waypoints: a via point, a gripper command, a minimum duration, scales below 1.
std::vector<core::JointWaypoint> waypoints() {
  Eigen::VectorXd q0(6), q1(6), q2(6), q3(6);
  q0 << 0.0, 0.5, -0.5, 0.0, 0.5, 0.0;
  q1 << 0.3, 0.6, -0.7, 0.1, 0.4, 0.2;
  q2 << 0.55, 0.45, -0.9, 0.2, 0.6, 0.1;
  q3 << 0.6, 0.4, -0.95, 0.2, 0.6, 0.1;
  return {{q0}, {q1, 0.0, std::nullopt, true}, {q2, 0.0, 0.1}, {q3, 1.5}};
}

core::TrajectoryOptions scales() {
  core::TrajectoryOptions options;
  options.velocity_scale = 0.5;
  options.acceleration_scale = 0.8;
  return options;
}

// %.17g: the YAML reads back the very doubles this process hashes.
std::string number(double value) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

std::string plan_yaml(const std::vector<core::JointWaypoint>& plan) {
  std::string yaml = "robot: puma560\nvelocity_scale: " + number(scales().velocity_scale) +
                     "\nacceleration_scale: " + number(scales().acceleration_scale) +
                     "\nwaypoints:\n";
  for (const core::JointWaypoint& w : plan) {
    yaml += "  - q_rad: [";
    for (int j = 0; j < w.q.size(); ++j) yaml += (j ? ", " : "") + number(w.q[j]);
    yaml += "]\n";
    if (w.min_duration > 0.0) yaml += "    min_duration_s: " + number(w.min_duration) + "\n";
    if (w.gripper) yaml += "    gripper: " + number(*w.gripper) + "\n";
    if (w.via) yaml += "    via: true\n";
  }
  return yaml;
}

class PlanHashCli : public ::testing::Test {
 protected:
  void SetUp() override {
    auto description = core::load_robot_description({"puma560", "", {}});
    ASSERT_TRUE(description) << description.error().message;
    model_ = description->model;
  }

  std::string write(const std::string& name, const std::vector<core::JointWaypoint>& plan) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path) << plan_yaml(plan);
    return path;
  }

  // This process's hash and duration of the same numbers.
  std::pair<std::string, double> in_process(const std::vector<core::JointWaypoint>& plan) {
    auto trajectory = core::Trajectory::create(*model_, plan, scales());
    EXPECT_TRUE(trajectory) << trajectory.error().message;
    if (!trajectory) return {};
    return {*core::plan_hash(*trajectory), trajectory->duration()};
  }

  test_files::TempDir tmp_{"plan_hash"};
  const std::filesystem::path dir_ = tmp_.path();
  core::RobotModelPtr model_;
};

TEST_F(PlanHashCli, AnotherProcessHashesThePlanAsThisOne) {
  const auto [hash, duration] = in_process(waypoints());
  ASSERT_EQ(hash.size(), 64u);
  const std::string file = write("plan.yaml", waypoints());
  const auto r = run_telear("plan hash --robot puma560 --plan " + file);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, hash + "\n");

  const auto j = run_telear("plan hash --robot puma560 --plan " + file + " --json");
  ASSERT_EQ(j.exit_code, 0) << j.err;
  const nlohmann::json json = nlohmann::json::parse(j.out);
  EXPECT_EQ(json["plan_hash"], hash);
  EXPECT_EQ(json["algorithm"], std::string(core::kTrajectoryAlgorithm));
  EXPECT_EQ(json["duration_s"].get<double>(), duration);  // to the bit
  EXPECT_EQ(json["waypoints"], 4);
}

TEST_F(PlanHashCli, ANanoradianChangesTheOtherProcesssHash) {
  std::vector<core::JointWaypoint> moved = waypoints();
  moved[2].q[1] += 1e-9;
  ASSERT_NE(moved[2].q[1], waypoints()[2].q[1]);
  const auto original =
      run_telear("plan hash --robot puma560 --plan " + write("a.yaml", waypoints()));
  const auto changed = run_telear("plan hash --robot puma560 --plan " + write("b.yaml", moved));
  ASSERT_EQ(original.exit_code, 0) << original.err;
  ASSERT_EQ(changed.exit_code, 0) << changed.err;
  EXPECT_NE(changed.out, original.out);
  EXPECT_EQ(changed.out, in_process(moved).first + "\n");
  // And the via point's waypoint too (it shifts the blend, not a stop).
  std::vector<core::JointWaypoint> via_moved = waypoints();
  via_moved[1].q[0] -= 1e-9;
  const auto via = run_telear("plan hash --robot puma560 --plan " + write("c.yaml", via_moved));
  ASSERT_EQ(via.exit_code, 0) << via.err;
  EXPECT_NE(via.out, original.out);
  EXPECT_EQ(via.out, in_process(via_moved).first + "\n");
}

TEST_F(PlanHashCli, BadInputIsOneLineAndExitCode2) {
  const auto missing =
      run_telear("plan hash --robot puma560 --plan " + (dir_ / "none.yaml").string());
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_THAT(missing.err, StartsWith("telear plan hash: "));
  EXPECT_TRUE(missing.out.empty());
  std::vector<core::JointWaypoint> beyond = waypoints();
  beyond[3].q[1] = 2.5;  // beyond the shoulder's limit
  const auto refused = run_telear("plan hash --robot puma560 --plan " + write("d.yaml", beyond));
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_THAT(refused.err, StartsWith("telear plan hash: "));
}

}  // namespace
}  // namespace telear
