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

// The corners of a ChArUco pattern seen in an 8-bit grey image (see above), with their ids.
// Errors say what was found: no marker, too few corners (fewer than `min_corners`), or
// corners all on one row or column of the board (no homography from them).
Result<DetectedPoints> detect_charuco(const cv::Mat& grey, const CalibrationPattern& pattern,
                                      int min_corners);

}  // namespace telear::vision
