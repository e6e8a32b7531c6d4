#pragma once
// ChArUco boards (OpenCV 4.6's aruco module, its pre-4.7 API): the board a "charuco:..."
// calibration pattern describes (telear/vision/calibration_pattern.hpp), its layout (for the
// simulator, which renders it as geometry), the image to print, and corner detection.
//
// Layout (cv::aruco::CharucoBoard::create, checked against its objPoints by the tests): SX x SY
// squares of side s in the target frame (x right, y down on the printed board, origin at the
// board's top-left outer corner); square (i, j) covers [i s, (i + 1) s] x [j s, (j + 1) s].
// The top-left square is black; the white squares hold the dictionary's markers 0, 1, 2, ...
// row by row, each centred in its square, upright (the marker image's top row at the smaller
// y). A marker of side m is (bits + 2) x (bits + 2) cells of m / (bits + 2): its bits inside a
// one-cell black border.
//
// Detection: cv::aruco::detectMarkers, cv::aruco::refineDetectedMarkers (finds markers the
// first pass missed, from the board's layout), then cv::aruco::interpolateCornersCharuco
// without a camera matrix (a local homography from the markers next to each corner, then
// cv::cornerSubPix), keeping a corner only where two of its neighbouring markers were found.
// A board partly hidden or out of frame yields the corners it shows.

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/vision/aruco_dictionary.hpp"
#include "telear/vision/calibration_pattern.hpp"

namespace telear::vision {

// The number of markers a board of sx x sy squares carries (its white squares).
int charuco_marker_count(int squares_x, int squares_y);

struct CharucoMarker {
  int id = 0;
  cv::Point2d top_left;  // of its black square, target frame, metres
  double side = 0.0;     // metres
  cv::Mat cells;         // CV_8U, (bits + 2) x (bits + 2), row 0 at the top: 0 black, 255 white
};

struct CharucoLayout {
  int squares_x = 0;
  int squares_y = 0;
  double square = 0.0;
  std::vector<int> marker_of_square;  // squares_y x squares_x, row by row: index or -1
  std::vector<CharucoMarker> markers;

  // Whether the square in column i, row j is black (i, j inside the board).
  bool black_square(int i, int j) const;
  // Reflectance of the printed board at target (x, y): 0 black, 1 white (also off the
  // board, where the paper is white).
  double reflectance(double x, double y) const;
};

// The layout of a ChArUco pattern (kind kCharuco, valid).
CharucoLayout charuco_layout(const CalibrationPattern& pattern);

// The board image to print (cv::aruco::CharucoBoard::draw): `pixels_per_square` pixels per
// square, inside a white margin of `margin_px` pixels. 8-bit grey.
cv::Mat draw_charuco_board(const CalibrationPattern& pattern, int pixels_per_square, int margin_px);

// Moves ChArUco corners from cv::aruco::interpolateCornersCharuco (OpenCV 4.6) onto the
// board's lines, in place, and drops those found hidden. `ids` are the corners' ids ((X - 1) per
// row, row by row), `corners` their pixels as cv::aruco gives them; `squares_x` the board's squares
// across, `marker_ratio` its marker side over its square side.
//
// Two faults of cv::aruco's corners are undone here. (1) Its refinement moves each corner by
// -(0.5, 0.5) px, calls cv::cornerSubPix and moves it back by +(0.5, 0.5): every corner it
// refines comes out half a pixel off in x and in y (cornerSubPix, like telear, puts pixel
// centres at integers). (2) Its cornerSubPix window is 1 px on a board whose white margin
// between a corner and the markers, (square - marker) / 2, is ~2 px in the image, and it stops
// at 0.1 px steps: its corners scatter by ~0.4 px RMS. A wider cornerSubPix window reaches the
// markers' edges and is pulled off the corner instead.
//
// So each corner is taken back by (0.5, 0.5) and then put where the board's row line and
// column line through it cross. Each line is the edge between the two black squares meeting
// at the corner and their white neighbours: on each half of it (from the corner towards the
// next corner, 15 % .. 85 % of the way) the edge is located, like a marker's border
// (telear/vision/marker_detection.hpp), where the grey profile along the edge's normal crosses
// the level midway between the black square and the white margin, searching from the black
// square outwards within 60 % of the margin (so that the marker beyond it is not reached: a
// margin of 1 px still works). A line is fitted to both halves' points by total least squares
// (black lies on opposite sides of the two halves, so a level set a little too low or too high
// moves them in opposite directions and the crossing stays put), and the two lines are
// intersected; three passes. The directions along and across each line come from the
// homography of the corners found (at least 4, not all on a line; fewer are only shifted). A
// corner keeps its shifted cv::aruco position when its edges cannot be measured (near the
// image border, too little contrast). A corner is dropped, with its id, when something covers
// its edges (the gripper in front of the board): an edge half found at fewer than half its
// points, fewer than 80 % of a line's points within 0.5 px of it, or the crossing more than a
// quarter square from cv::aruco's corner.
//
// Last, the lens: it bends the board's lines, and a straight line through a corner's two edge
// halves is a chord that passes beside the corner (on the simulated rig's lens, k1 = -0.28,
// 0.01-0.02 px towards the image centre, which placed a board 2.3 m away 0.2-0.3 mm too far;
// issue 26). Each edge is taken as a parabola about its line (src/vision/bent_edge.hpp), its
// bend the median of the bends of all the view's edges along the same board axis (one parabola
// per edge would double the corners' scatter), and each corner moved to where the two
// parabolas' tangents cross.
void refine_charuco_corners(const cv::Mat& grey, int squares_x, double marker_ratio,
                            std::vector<int>& ids, std::vector<cv::Point2f>& corners);

// The corners of a ChArUco pattern seen in an 8-bit grey image (see above), with their ids.
// Errors say what was found: no marker, too few corners (fewer than `min_corners`), or
// corners all on one row or column of the board (no homography from them).
Result<DetectedPoints> detect_charuco(const cv::Mat& grey, const CalibrationPattern& pattern,
                                      int min_corners);

}  // namespace telear::vision
