#pragma once
// Calibration targets: what a pattern spec string means, where the pattern's points are on
// the target, and how they are found in an image.
//
// Spec strings (the CLI's --pattern):
//   chessboard:COLSxROWS:SQUARE_M   COLS x ROWS *inner* corners (a 10 x 7-square board is
//                                   9x6), SQUARE_M the side of one square in metres.
//   circles:COLSxROWS:SPACING_M     OpenCV's asymmetric circle grid: ROWS rows of COLS
//                                   circles, every other row shifted by half a period.
//   charuco:SXxSY:SQUARE_M:MARKER_M:DICT
//                                   a ChArUco board (OpenCV's aruco module): SX x SY
//                                   *squares* (as cv::aruco::CharucoBoard::create counts
//                                   them), ArUco markers of side MARKER_M in the white
//                                   squares, from dictionary DICT (4x4_50 .. 6x6_1000 or
//                                   apriltag_36h11, OpenCV's DICT_ names without the prefix).
//                                   Its points are the (SX - 1) x (SY - 1) inner corners, so
//                                   cols x rows below count those, as for a chessboard.
//
// Object points (the target frame: z = 0 on the target, x along a row, y down the columns),
// in the order the detector returns image points (row-major, row r, column c):
//   chessboard   p(r, c) = (c s, r s, 0)
//   circles      p(r, c) = ((2 c + r mod 2) s, r s, 0)    (OpenCV's convention: circles in
//                one row are 2 s apart, neighbouring rows s apart and shifted by s)
//   charuco      p(r, c) = ((c + 1) s, (r + 1) s, 0)      (OpenCV 4.6's board frame: origin
//                at the outer corner of the top-left square of the printed board; the corner
//                at (r, c) has ChArUco id r cols + c, its index in pattern_object_points())
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
//   charuco      telear/vision/charuco_board.hpp: markers, then the corners between them.
//                A ChArUco board may be partly hidden or out of frame: detect_pattern_points()
//                returns the corners seen, with their ids; detect_pattern() only the whole
//                board (an error names how many of its corners were seen).

#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "telear/core/result.hpp"

namespace telear::vision {

enum class PatternKind { kChessboard, kAsymmetricCircles, kCharuco };

struct CalibrationPattern {
  PatternKind kind = PatternKind::kChessboard;
  int cols = 0;            // inner corners per row (chessboard) or circles per row
  int rows = 0;            // inner corners per column or rows of circles
  double spacing = 0.0;    // square side (chessboard, charuco) or s above (circles), metres
  double marker = 0.0;     // charuco: the side of a marker's black square, metres
  std::string dictionary;  // charuco: the ArUco dictionary, e.g. "4x4_50"

  int point_count() const { return cols * rows; }
  cv::Size size() const { return {cols, rows}; }
  // charuco: the board's squares per row and per column (inner corners + 1).
  int squares_x() const { return cols + 1; }
  int squares_y() const { return rows + 1; }
  // The spec string that parses back to this pattern, e.g. "chessboard:9x6:0.025".
  std::string spec() const;
};

// The points found in one image: pixel positions and, for each, its index in
// pattern_object_points() (for a ChArUco board its corner id; for the other patterns
// 0 .. point_count() - 1, every point, in order).
struct DetectedPoints {
  std::vector<cv::Point2f> image_points;
  std::vector<int> ids;
};

// The fewest ChArUco corners a view must show to count (a homography and a pose need 4
// points; 6 leave some redundancy against a wrongly interpolated corner).
inline constexpr int kMinCharucoCorners = 6;

// Parses a spec string; the error says which part is wrong and shows the expected form.
Result<CalibrationPattern> parse_calibration_pattern(const std::string& spec);

// The pattern's points in the target frame (see above), in detection order.
std::vector<cv::Point3f> pattern_object_points(const CalibrationPattern& pattern);

// Finds the whole pattern in an 8-bit grey or BGR image (see above). `pattern` must be valid.
// Errors: "no pattern found (...)"; for ChArUco also "only N of the board's M corners ...".
Result<std::vector<cv::Point2f>> detect_pattern(const cv::Mat& image,
                                                const CalibrationPattern& pattern);

// The pattern's points seen in an image: chessboard and circles as detect_pattern() (all or
// nothing); ChArUco the corners seen, at least `min_corners` of them not all on one line of
// the board (else an error saying how many were found and why they do not count).
Result<DetectedPoints> detect_pattern_points(const cv::Mat& image,
                                             const CalibrationPattern& pattern,
                                             int min_corners = kMinCharucoCorners);

// The object points of `ids` (indices into pattern_object_points()).
std::vector<cv::Point3f> pattern_object_points(const CalibrationPattern& pattern,
                                               const std::vector<int>& ids);

// The number of inner corners of the chessboard in `image` when it is larger than
// `pattern` (a chessboard pattern), else nullopt (same size, not found, or undecided).
std::optional<cv::Size> larger_chessboard(const cv::Mat& image, const CalibrationPattern& pattern);

// The cornerSubPix half-window used for detected chessboard corners: 0.3 x the smallest
// distance between row or column neighbours, rounded, clamped to 2 .. 15 pixels.
int subpixel_half_window(const std::vector<cv::Point2f>& corners,
                         const CalibrationPattern& pattern);

}  // namespace telear::vision
