// Google Benchmark program of the simulated stereo camera (sim::SimRigSource, the PUMA rig at
// 640 x 480): the cost of one captured pair per anti-aliasing mode, i.e. what the live video
// pays for where a marker's edges land (docs/demo.md, "Live overlay residual"):
//   build/bench/sim_camera_bench
// Arguments: supersample S (S x S pixels averaged), multisample M (MSAA samples per pixel).
// The Time column is the wall-clock time per stereo pair (ms).

#include <benchmark/benchmark.h>

#include <memory>

#include "telear/sim/sim_rig_source.hpp"

namespace {

void capture_pair(benchmark::State& state) {
  telear::sim::SimRigSourceOptions options;
  options.fps = 1000.0;  // the pacer never waits: the render is all that is timed
  options.supersample = static_cast<int>(state.range(0));
  options.multisample = static_cast<int>(state.range(1));
  auto source = telear::sim::SimRigSource::create(options);
  if (!source) {
    state.SkipWithError(source.error().message.c_str());
    return;
  }
  if (auto prepared = (*source)->prepare(); !prepared) {
    state.SkipWithError(prepared.error().message.c_str());
    return;
  }
  for (int i = 0; i < 3; ++i) (void)(*source)->capture();  // warm-up
  for (auto _ : state) {
    auto pair = (*source)->capture();
    if (!pair) {
      state.SkipWithError(pair.error().message.c_str());
      break;
    }
    benchmark::DoNotOptimize(pair->left.pixels.data());
  }
  (*source)->release();
}

}  // namespace

BENCHMARK(capture_pair)
    ->ArgNames({"supersample", "multisample"})
    ->Args({1, 1})
    ->Args({1, 2})
    ->Args({1, 4})
    ->Args({2, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

BENCHMARK_MAIN();
