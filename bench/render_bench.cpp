// Google Benchmark program of the renderer: the seed paper's Tables 1 and 2 (graphics only,
// on video; mono, stereo), one benchmark per case, on a headless EGL context. `telear bench
// render` times the same workload (bench/render_bench_command.hpp) and prints the table
// beside the seed's figures; this program is for profiling one case at a time, e.g.
//   build/bench/render_bench --benchmark_filter='video.*stereo'
// The Time column is the wall-clock time per frame (ms); the fps counter its inverse.

#include <benchmark/benchmark.h>

#include <cstdio>
#include <memory>
#include <string>

#include "bench/render_bench_command.hpp"
#include "telear/render/egl_context.hpp"

namespace {

void run_case(benchmark::State& state, const telear::cli::RenderBenchCase& c) {
  auto scene = telear::cli::RenderBenchScene::create(c, 640, 480);
  if (!scene) {
    state.SkipWithError(scene.error().message.c_str());
    return;
  }
  for (int i = 0; i < 10; ++i) (*scene)->frame();  // warm-up
  for (auto _ : state) (*scene)->frame();
  state.counters["fps"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

}  // namespace

int main(int argc, char** argv) {
  // One context for the whole program, current on the main thread, where benchmarks run.
  auto context = telear::render::create_headless_context();
  if (!context) {
    std::fprintf(stderr, "render_bench: %s\n", context.error().message.c_str());
    return 1;
  }
  std::printf("device: %s\n", (*context)->description().c_str());
  for (const telear::cli::RenderBenchCase& c : telear::cli::render_bench_cases()) {
    const std::string name = c.name + (c.stereo ? ", stereo" : ", mono");
    benchmark::RegisterBenchmark(name.c_str(), run_case, c)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
