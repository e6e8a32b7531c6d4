#pragma once
// `telear bench prediction`: the predictive display measured against the simulator's truth
// (issue 23, docs/benchmarks.md, "Prediction").
//
// The embedded simulated servers (lab::EmbeddedServers: the PUMA 560 and its stereo rig) on
// loopback, a session::Session whose video and robot states are both held back by the delay
// (SessionOptions::injected_video_delay_s and injected_state_delay_s: the whole link late),
// and a representative plan executed through it: from the demo's ready pose, `moves`
// joint-space moves (every joint at once, stopping at each waypoint) timed at `speed` of the
// arm's velocity and acceleration limits. At each display tick (`fps`) while the plan executes
// -- from the request until the session sees the robot's report that it finished -- the tool
// position the view draws (the predicted arm, session::ArmPredictor; without prediction, the
// last reported state) is compared with the simulated arm's true position at that tick
// (lab::PredictionErrorSeries). The goal at 400 ms: p95 <= 2 mm predicted and >= 10x smaller
// than without prediction.

#include <iosfwd>
#include <string>

namespace telear::cli {

struct PredictionBenchOptions {
  int delay_ms = 400;        // the video and the states held back on the client, 0..5000
  int moves = 3;             // moves of the plan after its start, 1..3
  double speed = 0.5;        // the plan's share of the velocity and acceleration limits, (0, 1]
  double fps = 30.0;         // display ticks per second, 1..120
  double camera_fps = 10.0;  // the simulated cameras' rate (they render on this machine)
  std::string json;          // also write the results as JSON to this file
};

int run_bench_prediction(const PredictionBenchOptions& options, std::ostream& out,
                         std::ostream& err);

}  // namespace telear::cli
