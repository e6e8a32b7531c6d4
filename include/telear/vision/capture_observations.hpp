#pragma once
// From a capture folder (telear/vision/capture_folder.hpp, what `telear capture` records) to
// hand-eye observations (telear/vision/hand_eye_registration.hpp): the target is detected in
// every saved image, as `telear register --captures DIR` does.
//
// Target: a registration target (telear/vision/registration_target.hpp: an ArUco marker, an
// AprilTag or a ChArUco board), by default the flange's ArUco marker
// (telear/core/marker_mount.hpp: dictionary, id, side). Its points are given in the target's
// own frame; where it sits on the flange is what the registration estimates. Each eye's
// points are averaged, point by point, over the frames of a pose that found them (the arm is
// at rest, so the average only lowers the sensor noise); a pose whose frames disagree by more
// than max_frame_spread_px in an eye keeps no points in that eye and is named (something
// moved during the capture). A board may be seen partly: the corners found are used, and a
// view with fewer than min_corners of them is named and not used in that eye; a board seen
// in one eye only at a pose is named too (that pose still counts, through the stereo pair).
// By default a view needs half the board's corners (at least 4): measured against the
// simulator's truth, views of a 4x4 board with 4 of its 9 corners were 0.07-0.6 px off (a link
// across the board, or one marker decoded), those with 5 or more 0.01-0.05 px, and one such
// view moved the registration by up to 0.7 mm (issue 26 item 1, docs/registration.md).

#include <array>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "telear/core/marker_mount.hpp"
#include "telear/core/result.hpp"
#include "telear/vision/capture_folder.hpp"
#include "telear/vision/hand_eye_registration.hpp"
#include "telear/vision/registration_target.hpp"

namespace telear::vision {

struct CaptureDetectionOptions {
  double max_frame_spread_px = 1.0;  // corners of one pose's frames further apart: moved
  int min_corners = 0;  // a board's corners in one eye, fewer: not used; 0: half the board's
                        // corners, at least 4 (min_board_corners)
};

// The corners of `target` (a board) one eye must see at a pose for that view to be used, when
// options.min_corners is 0: half the board's corners rounded up, at least 4.
int min_board_corners(const RegistrationTarget& target);

struct CaptureObservations {
  RegistrationTarget target;
  HandEyeObservations observations;
  std::vector<std::string> notes;  // per pose and eye: not found, moved, found in some frames
  int left_found = 0;              // poses whose target was found in the left eye
  int right_found = 0;
};

// `target` detected in both eyes of one captured frame, left then right, as
// detect_capture_targets detects it (every corner found, however few: min_corners 1). Errors:
// an image that cannot be read (naming it).
Result<std::array<TargetDetection, 2>> detect_in_captured_frame(const std::string& directory,
                                                                const CapturedFrame& frame,
                                                                const RegistrationTarget& target);

// Reads every image of `capture` (folder `directory`) and detects `target`; views are named
// "pose N" after the capture's order. Errors: an image that cannot be read (naming it).
Result<CaptureObservations> detect_capture_targets(const std::string& directory,
                                                   const CaptureSet& capture,
                                                   const RegistrationTarget& target,
                                                   const CaptureDetectionOptions& options = {});
// The same for the robot's marker (registration_target_from_mount).
Result<CaptureObservations> detect_capture_targets(const std::string& directory,
                                                   const CaptureSet& capture,
                                                   const core::MarkerMount& marker,
                                                   const CaptureDetectionOptions& options = {});

// Where the target has been seen in each eye: the two eyes side by side (each width x height,
// the cameras' image size), every pose's detected points drawn as their filled outline (the
// marker's quadrilateral, the convex hull of a board's seen corners; translucent, so overlaps
// show density) with the outline, a dot at each board corner and the pose number, and the
// uncovered image areas left dark -- what to capture next. BGR, for cv::imwrite.
cv::Mat coverage_image(const CaptureObservations& detected, int width, int height);

}  // namespace telear::vision
