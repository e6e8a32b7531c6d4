#pragma once
// From a capture folder (telear/vision/capture_folder.hpp, what `telear capture` records) to
// hand-eye observations (telear/vision/hand_eye_registration.hpp): the target is detected in
// every saved image, as `telear register --captures DIR` does.
//
// Target: the flange's ArUco marker (telear/core/marker_mount.hpp: dictionary, id, side). Its
// points are the marker's four corners in the marker's own frame; where it sits on the flange
// is what the registration estimates. Each eye's corners are averaged over the frames of a
// pose that found it (the arm is at rest, so the average only lowers the sensor noise); a
// pose whose frames disagree by more than max_frame_spread_px in an eye keeps no corners in
// that eye and is named (something moved during the capture).

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "telear/core/marker_mount.hpp"
#include "telear/core/result.hpp"
#include "telear/vision/capture_folder.hpp"
#include "telear/vision/hand_eye_registration.hpp"

namespace telear::vision {

struct CaptureDetectionOptions {
  double max_frame_spread_px = 1.0;  // corners of one pose's frames further apart: moved
};

struct CaptureObservations {
  HandEyeObservations observations;
  std::vector<std::string> notes;  // per pose and eye: not found, moved, found in some frames
  int left_found = 0;              // poses whose marker was found in the left eye
  int right_found = 0;
};

// The marker's corners in its own frame, in cv::aruco's order (marker_mount.hpp).
std::vector<Eigen::Vector3d> marker_target_points(const core::MarkerMount& marker);

// Reads every image of `capture` (folder `directory`) and detects `marker`; views are named
// "pose N" after the capture's order. Errors: an image that cannot be read (naming it).
Result<CaptureObservations> detect_capture_targets(const std::string& directory,
                                                   const CaptureSet& capture,
                                                   const core::MarkerMount& marker,
                                                   const CaptureDetectionOptions& options = {});

// Where the marker has been seen in each eye: the two eyes side by side (each width x height,
// the cameras' image size), every pose's detected marker drawn as a filled quadrilateral
// (translucent, so overlaps show density) with its outline and pose number, and the
// uncovered image areas left dark -- what to capture next. BGR, for cv::imwrite.
cv::Mat coverage_image(const CaptureObservations& detected, int width, int height);

}  // namespace telear::vision
