#pragma once
// `telear sim capture`: a calibration image set from the simulated stereo rig
// (docs/simulation.md, "Stereo rig"). Writes DIR/left_NN.png and DIR/right_NN.png (NN = 00,
// 01, ...) with the target at varied, well-conditioned poses, and DIR/truth.yaml: the true
// cameras in the camera-file format (OpenCV FileStorage YAML, left: / right:, each with its
// T_cam_base), the rig's baseline, the pattern, seed, noise, and per view the target's pose
// in the base frame and in the left camera.

#include <cstdint>
#include <ostream>
#include <string>

#include "telear/core/robot_loader.hpp"

namespace telear::cli {

struct SimCaptureOptions {
  std::string rig = core::data_directory() + "/rigs/puma560_rig.yaml";  // the shipped rig
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
