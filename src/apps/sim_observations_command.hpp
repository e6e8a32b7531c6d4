#pragma once
// `telear sim observations`: registration observations from the simulated robot and stereo
// rig (docs/registration.md, issue 4 item 5).
//
//   telear sim observations --rig data/rigs/puma560_rig.yaml --robot puma560 --configs 20
//                           -o obs.yaml [--seed S]
//
// Option parsing and printing around include/telear/sim/marker_observations.hpp, which says
// how the configurations are drawn and the marker detected. One line per configuration on
// `out`; a configuration seen by neither eye is skipped, and said so.
// Exit codes: 0 written, 2 bad options (one line on `err`), 1 the rig, robot, rendering or
// writing failed (one line on `err`).

#include <cstdint>
#include <iosfwd>
#include <string>

#include "telear/geometry/robot_selection.hpp"

#include "telear/sim/stereo_rig.hpp"

namespace telear::cli {

struct SimObservationsOptions : geometry::RobotSelection {
  std::string rig = sim::default_rig_file();  // the shipped rig
  int configs = 20;                           // configurations to render (1..500)
  std::string output;                         // observations YAML to write
  std::uint64_t seed = 1;                     // configurations and sensor noise
  double noise = 1.0;                         // sensor noise, grey levels (Gaussian sigma)
  int supersample = 4;                        // anti-aliasing factor per axis
  bool collision_free = false;                // only configurations free of contact
  double max_view_angle_deg = 55.0;
  double margin_px = 20.0;
};

int run_sim_observations(const SimObservationsOptions& options, std::ostream& out,
                         std::ostream& err);

}  // namespace telear::cli
