// Google Benchmark of the one time parameterization (core/trajectory.hpp) and the plan hash
// (core/plan_hash.hpp) on a 20-waypoint PUMA plan, and what sending it costs on the wire
// (net/command_bytes.hpp): the plan message, today's 100 Hz samples and a 100 Hz jog
// stream, reported as counters (bytes) of BM_CommandBytes. docs/benchmarks.md has figures:
//   build/bench/trajectory_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only
// The 20 waypoints are seeded random configurations (fixed seed), the same in every run.

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "telear/core/inverse_kinematics.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/plan_hash.hpp"
#include "telear/core/random_configuration.hpp"
#include "telear/core/robot_loader.hpp"
#include "telear/core/trajectory.hpp"
#include "telear/net/command_bytes.hpp"

namespace telear::bench {
namespace {

constexpr int kWaypoints = 20;

struct Plans {
  core::RobotModelPtr model;
  std::vector<core::JointWaypoint> stops, vias;

  static const Plans& get() {
    static const Plans plans = make();
    return plans;
  }

 private:
  static Plans make() {
    Plans p;
    auto model = core::load_robot("puma560");
    if (!model) {
      std::fprintf(stderr, "trajectory_bench: %s\n", model.error().message.c_str());
      std::exit(2);
    }
    p.model = *model;
    std::mt19937_64 rng(2026);
    for (int i = 0; i < kWaypoints; ++i) {
      // Within 40 % of the range around the middle: hops of a pick-and-place, not of a
      // wild random walk from limit to limit.
      const Eigen::VectorXd mid = 0.5 * (p.model->lower_limits() + p.model->upper_limits());
      p.stops.push_back({mid + 0.4 * (core::random_configuration(*p.model, rng) - mid)});
    }
    p.vias = p.stops;
    for (size_t k = 1; k + 1 < p.vias.size(); ++k) p.vias[k].via = true;
    return p;
  }
};

void parameterize(benchmark::State& state, bool via) {
  const Plans& plans = Plans::get();
  const auto& waypoints = via ? plans.vias : plans.stops;
  double duration = 0.0;
  for (auto _ : state) {
    auto trajectory = core::Trajectory::create(*plans.model, waypoints);
    benchmark::DoNotOptimize(trajectory);
    duration = trajectory->duration();
  }
  state.counters["duration_s"] = duration;
}

void BM_Parameterize20Stops(benchmark::State& state) {
  parameterize(state, false);
}
void BM_Parameterize20Vias(benchmark::State& state) {
  parameterize(state, true);
}

void BM_PlanHash20Vias(benchmark::State& state) {
  const Plans& plans = Plans::get();
  const core::Trajectory trajectory = *core::Trajectory::create(*plans.model, plans.vias);
  for (auto _ : state) {
    auto hash = core::plan_hash(trajectory);
    benchmark::DoNotOptimize(hash);
  }
}

// Parameterize and hash: what the server does with a plan message before executing it.
void BM_ParameterizeAndHash20Vias(benchmark::State& state) {
  const Plans& plans = Plans::get();
  for (auto _ : state) {
    auto trajectory = core::Trajectory::create(*plans.model, plans.vias);
    auto hash = core::plan_hash(*trajectory);
    benchmark::DoNotOptimize(hash);
  }
}

// Bytes, not time: one iteration computes them.
void BM_CommandBytes(benchmark::State& state) {
  const Plans& plans = Plans::get();
  const core::Trajectory trajectory = *core::Trajectory::create(*plans.model, plans.vias);
  const std::string lease(32, '0');  // the server's lease ids are 32 characters
  std::uint64_t plan_message = 0;
  net::CommandBytes samples;
  for (auto _ : state) {
    plan_message = *net::plan_message_bytes(trajectory, lease, "plan-1");
    samples = net::compare_command_bytes(*trajectory.sampled(100.0), 100.0, lease, "plan-1");
  }
  state.counters["plan_message_B"] = static_cast<double>(plan_message);
  state.counters["samples_100Hz_B"] = static_cast<double>(samples.plan_bytes);
  state.counters["jogs_100Hz_B"] = static_cast<double>(samples.jog_stream_bytes);
  state.counters["jog_messages"] = samples.jog_messages;
  state.counters["duration_s"] = trajectory.duration();
}

// A Cartesian segment (core/cartesian_segment.hpp): the PUMA's tool 0.22 m along a line while
// turning 25 deg, expanded (IK every step, chord checks) and timed, as the session's preview
// and the server's ExecutePlan do; and the same two waypoints in joint space.
void cartesian_line(benchmark::State& state, bool cartesian) {
  const Plans& plans = Plans::get();
  const core::RobotModel& model = *plans.model;
  Eigen::VectorXd qa(6);
  qa << 10.0, -40.0, 30.0, 15.0, 45.0, -20.0;
  qa *= std::numbers::pi / 180.0;
  Eigen::Isometry3d T =
      core::tool_pose(model, qa) * Eigen::AngleAxisd(std::numbers::pi * 25.0 / 180.0,
                                                     Eigen::Vector3d(1.0, 2.0, 0.0).normalized());
  T.translation() += Eigen::Vector3d(0.15, 0.10, -0.12);
  auto ik = core::solve_ik_nearest(model, T, qa);
  if (!ik) {
    state.SkipWithError(ik.error().message.c_str());
    return;
  }
  std::vector<core::JointWaypoint> waypoints{{qa}, {ik->q}};
  waypoints.back().cartesian = cartesian;
  std::size_t points = 0;
  for (auto _ : state) {
    auto trajectory = core::Trajectory::create(model, waypoints);
    if (!trajectory) {
      state.SkipWithError(trajectory.error().message.c_str());
      return;
    }
    points = trajectory->waypoints().size();
    benchmark::DoNotOptimize(trajectory->duration());
  }
  state.counters["waypoints"] = static_cast<double>(points);
}

void BM_CartesianLine(benchmark::State& state) {
  cartesian_line(state, true);
}
void BM_JointLine(benchmark::State& state) {
  cartesian_line(state, false);
}

BENCHMARK(BM_Parameterize20Stops)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CartesianLine)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_JointLine)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Parameterize20Vias)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PlanHash20Vias)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ParameterizeAndHash20Vias)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CommandBytes)->Iterations(1);

}  // namespace
}  // namespace telear::bench

BENCHMARK_MAIN();
