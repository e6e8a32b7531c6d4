#pragma once
// Calibration targets: what a pattern spec string means, where the pattern's points are on
// the target, and how they are found in an image.
//
// Spec strings (the CLI's --pattern):
//   chessboard:COLSxROWS:SQUARE_M   COLS x ROWS *inner* corners (a 10 x 7-square board is
//                                   9x6), SQUARE_M the side of one square in metres.
//   circles:COLSxROWS:SPACING_M     OpenCV's asymmetric circle grid: ROWS rows of COLS
//                                   circles, every other row shifted by half a period.
//
// Object points (the target frame: z = 0 on the target, x along a row, y down the columns),
// in the order the detector returns image points (row-major, row r, column c):
//   chessboard   p(r, c) = (c s, r s, 0)
//   circles      p(r, c) = ((2 c + r mod 2) s, r s, 0)    (OpenCV's convention: circles in
//                one row are 2 s apart, neighbouring rows s apart and shifted by s)
// Units are those of s; telear uses metres, but any unit works (the camera intrinsics do
// not depend on it, the stereo translation comes out in it).
//
// Detection returns `point_count()` pixel positions (OpenCV's convention: the centre of the
// top-left pixel is (0, 0)), or an error saying why there are none:
//   chessboard   cv::findChessboardCorners (adaptive threshold, normalized image; if that
//                fails, again on the image upsampled x2 as OpenCV's stereo_calib sample does,
//                for images up to 1024 x 1024),
//                then cv::cornerSubPix with a search half-window of 0.3 x the smallest
//                distance between neighbouring corners (2 .. 15 px). A fixed 11 px window
//                (the sample's) reaches into the neighbouring corners on small or oblique
//                boards: on OpenCV's own stereo set it doubles the calibration RMS
//                (0.44 px vs 0.20 px, docs/calibration.md).
//                A pattern smaller than the board (8x6 given for a 9x6 board) is found too,
//                on a part of the board that can differ from view to view; larger_chessboard()
//                tells (cv::findChessboardCornersSB with CALIB_CB_LARGER finds the whole
//                board); it costs a detection, so callers run it on a few images only.
//   circles      cv::findCirclesGrid(CALIB_CB_ASYMMETRIC_GRID) with a blob detector whose
//                area limit scales with the image, circle centres as blob centroids.

#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "telear/core/result.hpp"

namespace telear::vision {

enum class PatternKind { kChessboard, kAsymmetricCircles };

struct CalibrationPattern {
  PatternKind kind = PatternKind::kChessboard;
  int cols = 0;          // inner corners per row (chessboard) or circles per row
  int rows = 0;          // inner corners per column or rows of circles
  double spacing = 0.0;  // square side (chessboard) or s above (circles), metres

  int point_count() const { return cols * rows; }
  cv::Size size() const { return {cols, rows}; }
  // The spec string that parses back to this pattern, e.g. "chessboard:9x6:0.025".
  std::string spec() const;
};

// Parses a spec string; the error says which part is wrong and shows the expected form.
Result<CalibrationPattern> parse_calibration_pattern(const std::string& spec);

// The pattern's points in the target frame (see above), in detection order.
std::vector<cv::Point3f> pattern_object_points(const CalibrationPattern& pattern);

// Finds the pattern in an 8-bit grey or BGR image (see above). `pattern` must be valid.
// Errors: "no pattern found (...)" or "the board has more inner corners than 8x6 (...)".
Result<std::vector<cv::Point2f>> detect_pattern(const cv::Mat& image,
                                                const CalibrationPattern& pattern);

// The number of inner corners of the chessboard in `image` when it is larger than
// `pattern` (a chessboard pattern), else nullopt (same size, not found, or undecided).
std::optional<cv::Size> larger_chessboard(const cv::Mat& image, const CalibrationPattern& pattern);

// The cornerSubPix half-window used for detected chessboard corners: 0.3 x the smallest
// distance between row or column neighbours, rounded, clamped to 2 .. 15 pixels.
int subpixel_half_window(const std::vector<cv::Point2f>& corners,
                         const CalibrationPattern& pattern);

}  // namespace telear::vision
