#pragma once
// `telear sim observations`: registration observations from the simulated robot and stereo
// rig (docs/registration.md, issue 4 item 5).
//
//   telear sim observations --rig data/rigs/puma560_rig.yaml --robot puma560 --configs 20
//                           -o obs.yaml [--seed S]
//
// Draws seeded random in-limit joint configurations and keeps those at which the gripper's
// ArUco marker (telear/sim/calibration_targets.hpp) faces both cameras -- its face normal within
// `max_view_angle_deg` of the direction to each optical centre -- and all four corners
// project, with the true cameras, at least `margin_px` inside both images. At each kept
// configuration the "real" images are rendered per eye (telear/sim/scene_renderer.hpp: true
// distortion, sensor noise) and the marker's corners are DETECTED with cv::aruco
// (DICT_4X4_50), as on a real rig, then refined to sub-pixel precision by fitting lines to
// the black border's outer edges (cv::aruco's own refinement is only whole-pixel accurate on
// a ~20 px marker). An eye where the marker is not
// found gets an empty pixel list; a configuration seen by neither eye is skipped, and said so.
// The file's point_in_flange are the marker's corners in the flange frame, in detection order.
// Exit codes: 0 written, 2 bad input (one line on `err`), 1 rendering or writing failed.

#include <cstdint>
#include <iosfwd>
#include <string>

#include "telear/core/robot_loader.hpp"

namespace telear::cli {

struct SimObservationsOptions {
  std::string rig = core::data_directory() + "/rigs/puma560_rig.yaml";  // the shipped rig
  std::string robot = "puma560";  // the kinematics of the observations (and of the scene)
  int configs = 20;               // configurations to render (1..500)
  std::string output;             // observations YAML to write
  std::uint64_t seed = 1;         // configurations and sensor noise
  double noise = 1.0;             // sensor noise, grey levels (Gaussian sigma)
  int supersample = 4;            // anti-aliasing factor per axis
  double max_view_angle_deg = 55.0;
  double margin_px = 20.0;
};

int run_sim_observations(const SimObservationsOptions& options, std::ostream& out,
                         std::ostream& err);

}  // namespace telear::cli
