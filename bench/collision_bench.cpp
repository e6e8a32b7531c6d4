// Collision checking (geometry/collision_checker.hpp, trajectory_collision.hpp) against a naive
// baseline in the same run (docs/benchmarks.md):
//   Check/<arm>           one configuration: contacts and minimum clearance, bounds culling
//   CheckNaive/<arm>      the same configuration, every pair's distance, no culling
//   Plan10s/<arm>         a 10 s plan checked continuously (conservative advancement)
//   Plan10sNaive/<arm>    the same plan at fixed 10 ms samples, every pair's distance (which can
//                         still step over a thin obstacle)
// Arms: the PUMA 560 (primitives from its body file) and ur6 (STL collision meshes), each in
// its shipped table workspace; ur6_hulls: ur6's meshes as the convex hulls of their parts
// (geometry::MeshCollision::kConvexParts), the same configurations and plan. Run:
//   build/bench/collision_bench --benchmark_counters_tabular=true

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "telear/core/random_configuration.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/core/trajectory.hpp"
#include "telear/geometry/collision_checker.hpp"
#include "telear/geometry/trajectory_collision.hpp"
#include "telear/geometry/workspace_meshes.hpp"

namespace telear::bench {
namespace {

constexpr int kInputs = 256;
constexpr double kPlanDuration_s = 10.0;

template <typename T>
T or_exit(Result<T> result, const char* what) {
  if (!result) {
    std::fprintf(stderr, "collision_bench: %s: %s\n", what, result.error().message.c_str());
    std::exit(2);
  }
  return std::move(*result);
}

struct Arm {
  geometry::CollisionChecker checker;
  std::vector<Eigen::VectorXd> q;  // collision-free random configurations
  core::Trajectory plan;

  // `robot`, or `robot`_hulls: its mesh links as the convex hulls of their parts
  // (geometry::MeshCollision::kConvexParts), the same inputs and plan.
  static Arm& get(const std::string& name) {
    static std::map<std::string, Arm> arms;
    auto it = arms.find(name);
    if (it == arms.end()) it = arms.emplace(name, make(name)).first;
    return it->second;
  }

 private:
  static Arm make(const std::string& name) {
    const std::string suffix = "_hulls";
    const bool hulls = name.size() > suffix.size() &&
                       name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
    const std::string robot = hulls ? name.substr(0, name.size() - suffix.size()) : name;
    auto description = or_exit(core::load_robot_description({robot, "", {}}), "robot");
    auto workspace =
        or_exit(geometry::load_workspace(core::default_workspace_file(robot)), "workspace");
    if (hulls) {
      // The exact arm's inputs and plan, checked with the hulls.
      const Arm& exact = get(robot);
      geometry::CollisionSetupOptions options;
      options.mesh_collision = geometry::MeshCollision::kConvexParts;
      auto checker = or_exit(geometry::make_collision_checker(description, workspace, options),
                             "collision checker");
      return Arm{std::move(checker), exact.q, exact.plan};
    }
    // The meshes' triangles (convex parts are the default: the _hulls cases).
    geometry::CollisionSetupOptions exact_options;
    exact_options.mesh_collision = geometry::MeshCollision::kExact;
    auto checker = or_exit(geometry::make_collision_checker(description, workspace, exact_options),
                           "collision checker");
    // Seeded random configurations without contact: the inputs of the single checks, and the
    // waypoints of the plan (named configurations first, so the plan starts at the arm's
    // home pose).
    std::mt19937_64 rng(7);
    std::vector<Eigen::VectorXd> q;
    while (static_cast<int>(q.size()) < kInputs) {
      Eigen::VectorXd c = core::random_configuration(*description.model, rng);
      if (checker.check(c).collision_free()) q.push_back(c);
    }
    // The plan: from the arm's first named configuration (within the limits) through seeded
    // random configurations, each segment collision-free (a plan worth executing), until 10 s;
    // the last segment is stretched to make it exactly 10 s.
    const core::RobotModel& model = *description.model;
    std::vector<core::JointWaypoint> waypoints;
    for (const core::NamedConfiguration& c : model.named_configurations()) {
      if ((c.q.array() >= model.lower_limits().array()).all() &&
          (c.q.array() <= model.upper_limits().array()).all() &&
          checker.check(c.q).collision_free()) {
        waypoints.push_back({c.q});
        break;
      }
    }
    if (waypoints.empty()) waypoints.push_back({q[0]});
    auto duration = [&](const std::vector<core::JointWaypoint>& w) {
      return or_exit(core::Trajectory::create(model, w), "plan").duration();
    };
    for (std::size_t i = 0; i < q.size() && duration(waypoints) < kPlanDuration_s; ++i) {
      // A step of at most 0.8 rad per joint towards the random configuration.
      const Eigen::VectorXd& from = waypoints.back().q;
      const Eigen::VectorXd to = from + (q[i] - from).cwiseMax(-0.8).cwiseMin(0.8);
      auto segment = or_exit(core::Trajectory::create(model, {{from}, {to}}), "segment");
      auto report = or_exit(geometry::check_trajectory(checker, segment), "segment check");
      if (report.collision_free()) waypoints.push_back({to});
    }
    if (waypoints.size() < 2) {
      std::fprintf(stderr, "collision_bench: %s: no collision-free segment found\n", robot.c_str());
      std::exit(2);
    }
    while (waypoints.size() > 2 && duration(waypoints) > kPlanDuration_s) waypoints.pop_back();
    auto timed = or_exit(core::Trajectory::create(model, waypoints), "plan");
    waypoints.back().min_duration = kPlanDuration_s - timed.waypoint_times()[waypoints.size() - 2];
    auto plan = or_exit(core::Trajectory::create(model, waypoints), "plan");
    return Arm{std::move(checker), std::move(q), std::move(plan)};
  }
};

void Check(benchmark::State& state, const std::string& robot) {
  Arm& arm = Arm::get(robot);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(arm.checker.check(arm.q[i++ % arm.q.size()]));
  }
  state.counters["pairs"] = static_cast<double>(arm.checker.pairs().size());
}

void CheckNaive(benchmark::State& state, const std::string& robot) {
  Arm& arm = Arm::get(robot);
  std::size_t i = 0;
  for (auto _ : state) {
    arm.checker.set_configuration(arm.q[i++ % arm.q.size()], 0.5);
    benchmark::DoNotOptimize(arm.checker.min_distance_all_pairs());
  }
  state.counters["pairs"] = static_cast<double>(arm.checker.pairs().size());
}

void Plan10s(benchmark::State& state, const std::string& robot) {
  Arm& arm = Arm::get(robot);
  geometry::TrajectoryCheckReport report;
  for (auto _ : state) {
    auto r = geometry::check_trajectory(arm.checker, arm.plan);
    if (!r) {
      state.SkipWithError(r.error().message.c_str());
      return;
    }
    report = std::move(*r);
  }
  state.counters["plan_s"] = arm.plan.duration();
  state.counters["configs"] = static_cast<double>(report.evaluations);
  state.counters["distances"] = static_cast<double>(report.distance_queries);
  state.counters["contacts"] = static_cast<double>(report.collisions.size());
  state.counters["clearance_mm"] = report.min_clearance.distance_m * 1e3;
}

void Plan10sNaive(benchmark::State& state, const std::string& robot) {
  Arm& arm = Arm::get(robot);
  geometry::TrajectoryCheckReport report;
  for (auto _ : state) report = geometry::check_trajectory_sampled(arm.checker, arm.plan, 0.01);
  state.counters["plan_s"] = arm.plan.duration();
  state.counters["configs"] = static_cast<double>(report.evaluations);
  state.counters["distances"] = static_cast<double>(report.distance_queries);
  state.counters["contacts"] = static_cast<double>(report.collisions.size());
  state.counters["clearance_mm"] = report.min_clearance.distance_m * 1e3;
}

BENCHMARK_CAPTURE(Check, puma560, std::string("puma560"))->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(CheckNaive, puma560, std::string("puma560"))->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(Check, ur6, std::string("ur6"))->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(CheckNaive, ur6, std::string("ur6"))->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(Plan10s, puma560, std::string("puma560"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Plan10sNaive, puma560, std::string("puma560"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(Plan10s, ur6, std::string("ur6"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Plan10sNaive, ur6, std::string("ur6"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(Check, ur6_hulls, std::string("ur6_hulls"))->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(CheckNaive, ur6_hulls, std::string("ur6_hulls"))->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(Plan10s, ur6_hulls, std::string("ur6_hulls"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Plan10sNaive, ur6_hulls, std::string("ur6_hulls"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

}  // namespace
}  // namespace telear::bench

BENCHMARK_MAIN();
