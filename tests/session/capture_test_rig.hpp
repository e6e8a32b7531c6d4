#pragma once
// What the capture tests (automatic, manual, other targets, the console panel) set up the same
// way on the simulated PUMA 560 rig.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <filesystem>
#include <string>

#include "telear/core/marker_mount.hpp"
#include "telear/core/result.hpp"
#include "telear/core/robot_model.hpp"
#include "telear/sim/stereo_rig.hpp"
#include "test_util/temp_dir.hpp"

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
// both eyes. An error when none did. Rendered once per CTest run by the fixture
// puma560_marker_start (tests/CMakeLists.txt), whose file every capture test reads; a test run
// outside CTest, without that file, renders them itself.
Result<Eigen::VectorXd> marker_visible_start();

// The rig's true cameras written as `dir`/calibration.yaml, the calibration the vision server
// serves when registration, not calibration, is what a test measures. Returns the path.
Result<std::string> write_true_calibration(const sim::StereoRig& rig,
                                           const std::filesystem::path& dir);

// The fixture the capture tests derive from: the PUMA rig loaded, a folder of the test's own
// (CTest runs a fixture's cases in parallel processes) and the rig's true cameras written
// there as the calibration the vision server serves. A derived SetUp calls this one first and
// returns on HasFatalFailure().
//
// TELEAR_CAPTURE_TEST_KEEP=DIR copies the test's folder (its capture folders and the true
// calibration.yaml, the truth for `telear eval`) into DIR/<test name> at the end, so that the
// captures can be registered again offline (docs/registration.md, "Targets").
class CaptureRigTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;

  core::RobotModelPtr model;
  sim::StereoRig rig;
  core::MarkerMount marker;
  test_files::TempDir temp_dir{"capture"};
  std::filesystem::path dir;
  std::string calibration;  // dir/calibration.yaml
};

}  // namespace telear::test
