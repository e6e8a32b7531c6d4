#pragma once
// From image files to calibration views: glob expansion, decoding, pattern detection, stereo
// pairing, with a progress report per image and a record of every image left out and why.
//
// Pairs are matched in sorted file-name order (left01 with right01, ...). Images that cannot
// be decoded, whose size differs from the first decoded image, or that do not show the whole
// pattern are skipped (a stereo pair is skipped when either image is); an error is returned
// only for things that stop the whole run (no file matches, unequal left/right counts, a
// chessboard larger than the pattern says: checked on the first two images where it is
// found, see larger_chessboard()).
//
// ChArUco boards may be seen in part (detect_pattern_points()): a view counts with the
// corners it shows, at least kMinCharucoCorners, and carries their object points
// (PatternView::object_points); a stereo pair keeps the corners both images show (matched by
// id) and is skipped, saying how many each image had, when fewer than kMinCharucoCorners
// remain. A view with too few corners is skipped with the count in its reason.
//
// Stereo chessboards: OpenCV numbers the corners from either end of the board, so the two
// images of a pair can come back in opposite orders. The right list is reversed when the
// direction from the first to the last corner opposes the left's (a 180-degree turn, the
// only ambiguity of a board whose corner counts differ; square boards also have 90-degree
// ones, which is why boards like 9x6 are recommended).

#include <functional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/vision/calibration_pattern.hpp"
#include "telear/vision/mono_calibration.hpp"
#include "telear/vision/stereo_calibration.hpp"

namespace telear::vision {

// The files a shell glob pattern matches, sorted. An error when none does (the message says
// to check the directory and to quote the pattern).
Result<std::vector<std::string>> expand_image_glob(const std::string& pattern,
                                                   const std::string& option);

// Called after each image (mono) or pair (stereo): index from 1, count, the file names
// ("left01.png" or "left01.png + right01.png") and the outcome ("found", "no pattern found",
// "cannot decode image ...").
struct DetectionProgress {
  std::size_t index = 0;
  std::size_t count = 0;
  std::string name;
  bool found = false;
  std::string outcome;
};
using DetectionCallback = std::function<void(const DetectionProgress&)>;

struct MonoImageViews {
  cv::Size image_size;
  std::vector<PatternView> views;      // images with the pattern (ChArUco: enough of it)
  std::vector<RejectedView> rejected;  // images skipped, with the reason
};

struct StereoImageViews {
  cv::Size image_size;
  std::vector<StereoPatternView> views;
  std::vector<RejectedView> rejected;  // pairs skipped, with the reason
  int reordered_pairs = 0;             // pairs whose right corners were reversed (see above)
};

// Errors: an empty list, no image could be decoded, or the board is larger than the pattern.
Result<MonoImageViews> detect_in_images(const std::vector<std::string>& paths,
                                        const CalibrationPattern& pattern,
                                        const DetectionCallback& progress = {});

// Errors: empty lists, unequal counts, no pair could be decoded, or the board is larger
// than the pattern.
Result<StereoImageViews> detect_in_image_pairs(const std::vector<std::string>& left_paths,
                                               const std::vector<std::string>& right_paths,
                                               const CalibrationPattern& pattern,
                                               const DetectionCallback& progress = {});

// The file name without its directory.
std::string file_name_of(const std::string& path);

}  // namespace telear::vision
