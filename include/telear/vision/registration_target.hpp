#pragma once
// The target on the flange that hand-eye registration detects (docs/registration.md,
// "Targets"), chosen by a spec string as `--pattern` chooses a calibration pattern:
//
//   aruco:4x4_50:0:0.1               one ArUco marker: dictionary, id, side (m)
//   apriltag:36h11:3:0.08            one AprilTag (OpenCV's DICT_APRILTAG_36h11): family, id, side
//   charuco:5x5:0.05:0.038:4x4_50    a ChArUco board: squares x, squares y (as "XxY"), square
//                                    side (m), marker side (m), the markers' ArUco dictionary
//
// Dictionaries are OpenCV's predefined ones, written with or without "DICT_" and in any case
// (4x4_50, DICT_4X4_50). A marker's side is its black square's (the detector's corners); the
// printed marker needs a white quiet zone around it. A board's markers sit in its white
// squares, as cv::aruco::CharucoBoard::create (OpenCV 4.6) lays them out.
//
// Target frame, for every kind (the robot's marker mount, telear/core/marker_mount.hpp, places
// it on the flange): origin at the target's centre, x to the right and y up as printed, z out
// of the face towards the viewer. Points:
//   marker  its four corners in cv::aruco's order: (-L/2, L/2, 0), (L/2, L/2, 0),
//           (L/2, -L/2, 0), (-L/2, -L/2, 0) (point ids 0..3);
//   board   the (X - 1) x (Y - 1) inner chessboard corners in cv::aruco's charuco id order
//           (row by row from the printed top-left), at ((i + 1) s - X s / 2, Y s / 2 - (j + 1) s,
//           0) for corner id j (X - 1) + i.
//
// Detection returns the point ids seen and their raw pixels (OpenCV's convention, the centre
// of the top-left pixel is (0, 0)). A marker is found only when its id appears at one place;
// its corners are refined on the black border's outer edges (marker_detection.hpp). A board's
// markers are detected, then its chessboard corners interpolated from them
// (cv::aruco::interpolateCornersCharuco, each corner from its neighbouring markers, refined by
// cornerSubPix): a partial view gives the corners near the markers found.

#include <Eigen/Core>
#include <array>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "telear/core/marker_mount.hpp"
#include "telear/core/result.hpp"

namespace telear::vision {

enum class TargetKind { kAruco, kAprilTag, kCharuco };

struct RegistrationTarget {
  TargetKind kind = TargetKind::kAruco;
  std::string dictionary = "DICT_4X4_50";  // OpenCV's name (the markers' for a board)
  int id = 0;                              // marker kinds
  double side_m = 0.1;                     // marker kinds: the black square's side
  int squares_x = 0;                       // board: squares across, printed left to right
  int squares_y = 0;                       // board: squares down
  double square_m = 0.0;                   // board: a chessboard square's side
  double marker_m = 0.0;                   // board: its markers' side

  bool is_board() const { return kind == TargetKind::kCharuco; }
  // The canonical spec ("charuco:5x5:0.05:0.038:4x4_50"); parses back to the same target.
  std::string spec() const;
  // e.g. "ArUco marker 0 (DICT_4X4_50, 0.1 m)", "ChArUco board 5x5 (0.05 m squares)".
  std::string description() const;
  // The points above in the target frame, indexed by point id.
  std::vector<Eigen::Vector3d> points() const;
  // The printed extent (m) in x and y, a marker's one-cell quiet zone or a board's white
  // margin of half a square included: what must fit on the flange.
  Eigen::Vector2d printed_size_m() const;
  // Cells per side of one marker, border included (4x4: 6; AprilTag 36h11: 8).
  int marker_cells() const;
};

// Errors quote the spec and say what was expected: an unknown kind or dictionary, a wrong
// number of fields, ids outside the dictionary, sizes that are not positive numbers, a board
// with fewer than 2 squares a side, a marker not smaller than its square, a board with more
// markers than its dictionary holds.
Result<RegistrationTarget> parse_registration_target(const std::string& spec);

// The robot's mounted marker (marker_mount.hpp) as a target: today's default.
RegistrationTarget registration_target_from_mount(const core::MarkerMount& mount);

struct TargetDetectionOptions {
  bool refine = true;   // marker kinds: refine_marker_corners
  int min_corners = 4;  // board: fewer interpolated corners count as not found
};

struct TargetDetection {
  std::vector<int> ids;                 // point ids, ascending
  std::vector<Eigen::Vector2d> pixels;  // raw pixels, one per id
  int markers_found = 0;                // board: its markers decoded
  int corners_seen = 0;                 // board: corners interpolated (even when too few)
  bool found() const { return !ids.empty(); }
};

// `image`: 8-bit grey (CV_8UC1), RGB (CV_8UC3, telear's channel order) or RGBA (CV_8UC4).
// No ids when not found (a board: fewer than options.min_corners corners; markers_found and
// corners_seen then say how much was seen).
TargetDetection detect_registration_target(const cv::Mat& image, const RegistrationTarget& target,
                                           const TargetDetectionOptions& options = {});

// The target's dark areas as quadrilaterals in the target frame (z = 0; corners in printed
// order top-left, top-right, bottom-right, bottom-left): every black cell of every marker and
// a board's black squares. White is everything else inside printed_size_m(). The simulator
// draws these; registration_target_image() prints them.
std::vector<std::array<Eigen::Vector3d, 4>> registration_target_dark_quads(
    const RegistrationTarget& target);

// The printable image of the target (white background, quiet zone / margin included) at
// `pixels_per_m` (e.g. 300 dpi = 11811 px/m): what to print, and what the simulator draws.
cv::Mat registration_target_image(const RegistrationTarget& target, double pixels_per_m);

}  // namespace telear::vision
