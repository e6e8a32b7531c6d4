#pragma once
// `telear register`: the robot base's pose in each camera of a calibrated stereo pair
// (docs/registration.md).
//
//   telear register --rig stereo.yaml --robot puma560 --observations obs.yaml -o out.yaml
//
// --rig is a stereo camera file (intrinsics and distortion per eye) with the pair's geometry
// T_right_left: the R, T keys of a stereo `telear calibrate` (X_R = R X_L + T), or, for a file
// that already has both T_cam_base (a registered file, a simulator's truth.yaml),
// T_right_base T_left_base^-1. telear/vision/registration.hpp solves for T_left_base with that
// geometry held fixed. The output is the camera file with T_cam_base set for both eyes plus
// R and T (so it can be registered again); the calibration's other stereo keys (E, F, the
// rectification) are not carried over. It is written atomically: no partial file on failure.
// Prints the residual RMS / max per eye after the PnP start and after the joint refinement,
// and the number of observations.
//
//   telear register --captures DIR [--rig stereo.yaml] --robot puma560 -o out.yaml
//
// detects the robot's marker in a capture folder's images and solves the hand-eye
// registration (the base in both cameras and the marker on the flange, jointly;
// telear/vision/capture_registration.hpp); --rig defaults to the folder's own camera file. Exit
// codes: 0 done, 2 bad input (one line on `err`), 1 the output could not be written.

#include <iosfwd>
#include <string>

#include "telear/geometry/robot_selection.hpp"

namespace telear::cli {

struct RegisterOptions : geometry::RobotSelection {
  std::string rig;           // stereo camera file (calibration output)
  std::string observations;  // observations YAML (telear/vision/observations_file.hpp)
  std::string captures;      // a capture folder (telear capture); --rig optional then
  std::string target;        // --target SPEC; empty: the capture's recorded one, else the marker
  std::string output;        // camera file to write (may equal --rig)
  int max_iterations = 100;  // Levenberg-Marquardt
};

int run_register(const RegisterOptions& options, std::ostream& out, std::ostream& err);

}  // namespace telear::cli
