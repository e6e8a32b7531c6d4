#pragma once
// `telear register --captures DIR`: a capture folder (telear/vision/capture_folder.hpp) to a
// registered stereo camera file, as a library call (docs/registration.md, "Register your real
// cameras"). Loads the folder, takes the stereo calibration from `rig_file` or, when that is
// empty, from the folder's own camera file (what the vision server reported at capture
// time), detects the flange's target in every image (capture_observations.hpp) and solves the
// hand-eye registration (hand_eye_registration.hpp).
//
// The target: `target` when given (`telear register --target SPEC`), else the one the capture
// folder names (capture.yaml `target:`, what `telear capture` recorded), else the robot's
// marker `marker` (telear/core/marker_mount.hpp).

#include <Eigen/Geometry>
#include <optional>
#include <string>

#include "telear/core/marker_mount.hpp"
#include "telear/core/result.hpp"
#include "telear/core/robot_model.hpp"
#include "telear/vision/camera_model.hpp"
#include "telear/vision/capture_folder.hpp"
#include "telear/vision/capture_observations.hpp"
#include "telear/vision/hand_eye_registration.hpp"

namespace telear::vision {

struct CaptureRegistration {
  CaptureSet capture;
  std::string camera_file;  // the stereo calibration used
  CaptureObservations detected;
  HandEyeResult result;
  StereoCameraModel registered;  // the calibration with both T_cam_base from `result`
  Eigen::Isometry3d T_right_left = Eigen::Isometry3d::Identity();
};

// Errors name the folder or file and say what to do: no capture there, no calibration (give
// --rig), a mono calibration, a capture of another robot (its joint count), a capture whose
// target spec does not parse, and the registration's own (too few poses, degenerate, poorly
// conditioned).
Result<CaptureRegistration> register_captures(
    const core::RobotModel& model, const std::string& directory, const std::string& rig_file,
    const core::MarkerMount& marker, const HandEyeOptions& options = {},
    const std::optional<RegistrationTarget>& target = std::nullopt);

// The report the CLI prints: poses and detections, notes, per-pose residuals, the solution
// with its 1-sigma uncertainty, and the closed-form baseline beside it.
std::string capture_registration_report(const CaptureRegistration& registration);

}  // namespace telear::vision
