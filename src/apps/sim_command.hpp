#pragma once
// `telear sim capture`: a calibration image set from the simulated stereo rig
// (docs/simulation.md, "Stereo rig"): option parsing and printing around
// include/telear/sim/calibration_capture.hpp, which says what DIR holds afterwards (left_NN.png,
// right_NN.png, truth.yaml). Exit codes: 0 written, 2 bad options, 1 the rig, rendering or
// writing failed (one line on `err`).

#include <cstdint>
#include <ostream>
#include <string>

#include "telear/sim/stereo_rig.hpp"

namespace telear::cli {

struct SimCaptureOptions {
  std::string rig = sim::default_rig_file();  // the shipped rig
  std::string pattern = "chessboard:9x6:0.03";
  int views = 20;
  std::string output;      // directory, created if missing
  std::uint64_t seed = 1;  // poses and sensor noise
  double noise = 1.0;      // sensor noise, grey levels (Gaussian sigma)
  int supersample = 4;     // anti-aliasing factor per axis
  bool no_scene = false;   // the target alone on the background (no robot, floor, table)
};

int run_sim_capture(const SimCaptureOptions& options, std::ostream& out, std::ostream& err);

}  // namespace telear::cli
