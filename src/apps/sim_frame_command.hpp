#pragma once
// `telear sim frame`: one stereo pair of the simulated "real" scene — the arm with its real
// body, the table, the floor — at a given joint configuration, through the rig's true cameras
// with their lens distortion and sensor noise. It is the video frame the ghost is drawn on
// (`telear render --background PREFIX_left.png,PREFIX_right.png`).

#include <cstdint>
#include <ostream>
#include <string>

#include "telear/sim/stereo_rig.hpp"

namespace telear::cli {

struct SimFrameOptions {
  std::string rig = sim::default_rig_file();  // the shipped rig
  std::string q = "qr";  // joint values (rad, or deg with `degrees`) or a named configuration
  bool degrees = false;
  double gripper = 0.04;   // gripper opening, m
  std::string output;      // PREFIX: writes PREFIX_left.png and PREFIX_right.png
  std::uint64_t seed = 1;  // sensor noise
  double noise = 1.0;      // grey levels (Gaussian sigma)
  int supersample = 4;     // anti-aliasing (sim::SceneOptions): the stills' quality
  int multisample = 1;     // MSAA samples per pixel (sim::SceneOptions)
};

int run_sim_frame(const SimFrameOptions& options, std::ostream& out, std::ostream& err);

}  // namespace telear::cli
