#pragma once
// What the capture tests (automatic, manual, other targets, the console panel) set up the same
// way on the simulated PUMA 560 rig.

#include <Eigen/Core>
#include <filesystem>
#include <string>

#include "telear/core/marker_mount.hpp"
#include "telear/core/result.hpp"
#include "telear/core/robot_model.hpp"
#include "telear/sim/stereo_rig.hpp"

namespace telear::test {

// The shipped PUMA 560, its default rig and its marker mount. Errors say which failed to load.
struct PumaCaptureRig {
  core::RobotModelPtr model;
  sim::StereoRig rig;
  core::MarkerMount marker;
};
Result<PumaCaptureRig> load_puma_capture_rig();

// Where the operator jogs the arm before capturing: the first configuration at which the
// default PUMA rig's own rendered observations (seed 2, 4 configurations) found the marker in
// both eyes. An error when none did.
Result<Eigen::VectorXd> marker_visible_start();

// The rig's true cameras written as `dir`/calibration.yaml, the calibration the vision server
// serves when registration, not calibration, is what a test measures. Returns the path.
Result<std::string> write_true_calibration(const sim::StereoRig& rig,
                                           const std::filesystem::path& dir);

}  // namespace telear::test
