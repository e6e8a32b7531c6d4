#include "telear/vision/calibration_pattern.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <opencv2/calib3d.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "telear/core/number_list.hpp"
#include "telear/vision/charuco_board.hpp"

namespace telear::vision {
namespace {

constexpr int kMaxPatternSide = 200;

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string::size_type begin = 0;
  while (true) {
    const auto end = text.find(separator, begin);
    parts.push_back(text.substr(begin, end - begin));
    if (end == std::string::npos) break;
    begin = end + 1;
  }
  return parts;
}

std::optional<int> parse_int(const std::string& text) {
  int value = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || ptr != text.data() + text.size()) return std::nullopt;
  return value;
}

cv::Mat to_grey(const cv::Mat& image) {
  if (image.channels() == 1) return image;
  cv::Mat grey;
  cv::cvtColor(image, grey, image.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  return grey;
}

std::string not_found(const CalibrationPattern& pattern) {
  return "no pattern found (the whole " + pattern.spec() +
         " must be visible; COLSxROWS counts inner corners)";
}

Result<std::vector<cv::Point2f>> detect_chessboard(const cv::Mat& grey,
                                                   const CalibrationPattern& pattern) {
  std::vector<cv::Point2f> corners;
  const int flags = cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE;
  bool found = cv::findChessboardCorners(grey, pattern.size(), corners, flags);
  if (!found && grey.cols <= 1024 && grey.rows <= 1024) {
    // Small boards: the quad detector needs a few pixels per square (OpenCV's sample does the
    // same). Corners found at scale 2 are brought back and refined on the original image.
    // Not for large images, where squares are rarely that small and the search is slow.
    cv::Mat larger;
    cv::resize(grey, larger, cv::Size(), 2.0, 2.0, cv::INTER_LINEAR_EXACT);
    found = cv::findChessboardCorners(larger, pattern.size(), corners, flags);
    if (found) {
      for (cv::Point2f& p : corners) p *= 0.5f;
    }
  }
  if (!found) return Error{not_found(pattern)};
  const int half = subpixel_half_window(corners, pattern);
  cv::cornerSubPix(grey, corners, cv::Size(half, half), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 50, 1e-3));
  return corners;
}

Result<std::vector<cv::Point2f>> detect_circles(const cv::Mat& grey,
                                                const CalibrationPattern& pattern) {
  // OpenCV's default blob detector caps the blob area at 5000 px^2, which misses the circles
  // of a target filling a high-resolution image: allow up to one grid cell's area.
  cv::SimpleBlobDetector::Params params;
  params.minArea = 10.0f;
  params.maxArea = std::max(
      5000.0f, static_cast<float>(grey.total()) / static_cast<float>(pattern.point_count()));
  const cv::Ptr<cv::FeatureDetector> blobs = cv::SimpleBlobDetector::create(params);
  std::vector<cv::Point2f> centres;
  if (!cv::findCirclesGrid(grey, pattern.size(), centres, cv::CALIB_CB_ASYMMETRIC_GRID, blobs)) {
    return Error{not_found(pattern)};
  }
  return centres;
}

// Shortest text that reads back as the same double ("0.03", not "0.029999999999999999").
std::string shortest(double value) {
  char number[32];
  const auto end = std::to_chars(number, number + sizeof number, value).ptr;
  return std::string(number, end);
}

Result<CalibrationPattern> parse_charuco(const std::vector<std::string>& parts,
                                         const std::string& where) {
  const std::string form =
      " (expected charuco:SXxSY:SQUARE_M:MARKER_M:DICT, e.g. charuco:7x5:0.04:0.03:4x4_50 for "
      "a board of 7x5 squares of 40 mm with 30 mm markers of DICT_4X4_50)";
  if (parts.size() != 5) {
    return Error{where + "not five fields separated by ':'" + form};
  }
  const std::vector<std::string> size = split(parts[1], 'x');
  const std::optional<int> sx = size.size() == 2 ? parse_int(size[0]) : std::nullopt;
  const std::optional<int> sy = size.size() == 2 ? parse_int(size[1]) : std::nullopt;
  if (!sx || !sy) return Error{where + "size '" + parts[1] + "' is not SXxSY" + form};
  if (*sx < 3 || *sy < 3 || *sx > kMaxPatternSide + 1 || *sy > kMaxPatternSide + 1) {
    return Error{where + "size " + parts[1] +
                 " is out of range: a ChArUco board needs 3 to 201 squares per side (SXxSY "
                 "counts squares, not inner corners: 7x5 squares have 6x4 corners)"};
  }
  CalibrationPattern pattern;
  pattern.kind = PatternKind::kCharuco;
  pattern.cols = *sx - 1;
  pattern.rows = *sy - 1;

  const Result<double> square = core::parse_number(parts[2], "square size");
  if (!square || *square <= 0.0) {
    return Error{where + "square size '" + parts[2] +
                 "' is not a positive number (the side of a square in metres, e.g. 0.04)"};
  }
  const Result<double> marker = core::parse_number(parts[3], "marker size");
  if (!marker || *marker <= 0.0) {
    return Error{where + "marker size '" + parts[3] +
                 "' is not a positive number (the side of a marker in metres, e.g. 0.03)"};
  }
  if (*marker >= *square) {
    return Error{where + "marker size " + parts[3] + " m is not smaller than the square size " +
                 parts[2] +
                 " m (a marker sits inside a white square with a white border; "
                 "typically 0.6-0.8 of the square)"};
  }
  pattern.spacing = *square;
  pattern.marker = *marker;

  const std::optional<std::string> dictionary = canonical_aruco_dictionary(parts[4]);
  if (!dictionary) {
    std::string names;
    for (const std::string& name : aruco_dictionary_names()) {
      names += (names.empty() ? "" : ", ") + name;
    }
    return Error{where + "unknown dictionary '" + parts[4] + "' (one of " + names + ")"};
  }
  pattern.dictionary = *dictionary;
  const int markers = charuco_marker_count(*sx, *sy);
  if (markers > aruco_dictionary_size(*dictionary)) {
    return Error{where + "a board of " + parts[1] + " squares carries " + std::to_string(markers) +
                 " markers but dictionary " + *dictionary + " has only " +
                 std::to_string(aruco_dictionary_size(*dictionary)) +
                 "; use a larger dictionary or fewer squares"};
  }
  return pattern;
}

}  // namespace

std::string CalibrationPattern::spec() const {
  if (kind == PatternKind::kCharuco) {
    return "charuco:" + std::to_string(squares_x()) + "x" + std::to_string(squares_y()) + ":" +
           shortest(spacing) + ":" + shortest(marker) + ":" + dictionary;
  }
  return std::string(kind == PatternKind::kChessboard ? "chessboard" : "circles") + ":" +
         std::to_string(cols) + "x" + std::to_string(rows) + ":" + shortest(spacing);
}

Result<CalibrationPattern> parse_calibration_pattern(const std::string& spec) {
  const std::string where = "pattern '" + spec + "': ";
  const std::string form =
      " (expected chessboard:COLSxROWS:SQUARE_M, e.g. chessboard:9x6:0.025 for a board of "
      "10x7 squares of 25 mm, circles:COLSxROWS:SPACING_M, e.g. circles:4x11:0.02, or "
      "charuco:SXxSY:SQUARE_M:MARKER_M:DICT, e.g. charuco:7x5:0.04:0.03:4x4_50)";
  const std::vector<std::string> parts = split(spec, ':');
  if (parts[0] == "charuco") return parse_charuco(parts, where);
  if (parts.size() != 3) return Error{where + "not three fields separated by ':'" + form};

  CalibrationPattern pattern;
  if (parts[0] == "chessboard") {
    pattern.kind = PatternKind::kChessboard;
  } else if (parts[0] == "circles") {
    pattern.kind = PatternKind::kAsymmetricCircles;
  } else {
    return Error{where + "unknown kind '" + parts[0] + "'" + form};
  }

  const std::vector<std::string> size = split(parts[1], 'x');
  const std::optional<int> cols = size.size() == 2 ? parse_int(size[0]) : std::nullopt;
  const std::optional<int> rows = size.size() == 2 ? parse_int(size[1]) : std::nullopt;
  if (!cols || !rows) return Error{where + "size '" + parts[1] + "' is not COLSxROWS" + form};
  pattern.cols = *cols;
  pattern.rows = *rows;
  const int min_cols = pattern.kind == PatternKind::kChessboard ? 3 : 2;
  if (pattern.cols < min_cols || pattern.rows < 3 || pattern.cols > kMaxPatternSide ||
      pattern.rows > kMaxPatternSide) {
    return Error{where + "size " + parts[1] + " is out of range: " +
                 (pattern.kind == PatternKind::kChessboard
                      ? "a chessboard needs 3 to 200 inner corners per side (count the "
                        "corners where four squares meet: a board of 10x7 squares is 9x6)"
                      : "a circle grid needs 2 to 200 circles per row and 3 to 200 rows")};
  }

  const Result<double> spacing = core::parse_number(parts[2], "spacing");
  if (!spacing || *spacing <= 0.0) {
    return Error{where + "spacing '" + parts[2] +
                 "' is not a positive number (the square side or circle spacing in metres, "
                 "e.g. 0.025)"};
  }
  pattern.spacing = *spacing;
  return pattern;
}

std::vector<cv::Point3f> pattern_object_points(const CalibrationPattern& pattern) {
  std::vector<cv::Point3f> points;
  points.reserve(static_cast<std::size_t>(pattern.point_count()));
  const double s = pattern.spacing;
  for (int r = 0; r < pattern.rows; ++r) {
    for (int c = 0; c < pattern.cols; ++c) {
      if (pattern.kind == PatternKind::kCharuco) {
        points.emplace_back(static_cast<float>((c + 1) * s), static_cast<float>((r + 1) * s), 0.0f);
        continue;
      }
      const double x = pattern.kind == PatternKind::kChessboard ? c * s : (2 * c + r % 2) * s;
      points.emplace_back(static_cast<float>(x), static_cast<float>(r * s), 0.0f);
    }
  }
  return points;
}

std::vector<cv::Point3f> pattern_object_points(const CalibrationPattern& pattern,
                                               const std::vector<int>& ids) {
  const std::vector<cv::Point3f> all = pattern_object_points(pattern);
  std::vector<cv::Point3f> points;
  points.reserve(ids.size());
  for (int id : ids) points.push_back(all.at(static_cast<std::size_t>(id)));
  return points;
}

int subpixel_half_window(const std::vector<cv::Point2f>& corners,
                         const CalibrationPattern& pattern) {
  assert(static_cast<int>(corners.size()) == pattern.point_count());
  double nearest = std::numeric_limits<double>::infinity();
  for (int r = 0; r < pattern.rows; ++r) {
    for (int c = 0; c < pattern.cols; ++c) {
      const cv::Point2f& p = corners[static_cast<std::size_t>(r * pattern.cols + c)];
      if (c + 1 < pattern.cols) {
        nearest = std::min(
            nearest, cv::norm(p - corners[static_cast<std::size_t>(r * pattern.cols + c + 1)]));
      }
      if (r + 1 < pattern.rows) {
        nearest = std::min(
            nearest, cv::norm(p - corners[static_cast<std::size_t>((r + 1) * pattern.cols + c)]));
      }
    }
  }
  return std::clamp(static_cast<int>(std::lround(0.3 * nearest)), 2, 15);
}

std::optional<cv::Size> larger_chessboard(const cv::Mat& image, const CalibrationPattern& pattern) {
  assert(pattern.kind == PatternKind::kChessboard);
  std::vector<cv::Point2f> corners;
  cv::Mat meta;
  bool found = false;
  try {
    found = cv::findChessboardCornersSB(to_grey(image), pattern.size(), corners,
                                        cv::CALIB_CB_NORMALIZE_IMAGE | cv::CALIB_CB_LARGER, meta);
  } catch (const cv::Exception&) {
    return std::nullopt;
  }
  if (!found || static_cast<int>(corners.size()) <= pattern.point_count()) return std::nullopt;
  // meta is the found board's grid, in either orientation: report it in the pattern's.
  if (meta.cols >= pattern.cols && meta.rows >= pattern.rows) return cv::Size(meta.cols, meta.rows);
  return cv::Size(meta.rows, meta.cols);
}

Result<std::vector<cv::Point2f>> detect_pattern(const cv::Mat& image,
                                                const CalibrationPattern& pattern) {
  assert(!image.empty() && image.depth() == CV_8U);
  const cv::Mat grey = to_grey(image);
  switch (pattern.kind) {
    case PatternKind::kChessboard:
      return detect_chessboard(grey, pattern);
    case PatternKind::kAsymmetricCircles:
      return detect_circles(grey, pattern);
    case PatternKind::kCharuco:
      break;
  }
  auto found = detect_charuco(grey, pattern, kMinCharucoCorners);
  if (!found) return found.error();
  if (static_cast<int>(found->ids.size()) < pattern.point_count()) {
    return Error{"only " + std::to_string(found->ids.size()) + " of the board's " +
                 std::to_string(pattern.point_count()) + " ChArUco corners found (the whole " +
                 pattern.spec() + " must be visible here)"};
  }
  std::vector<cv::Point2f> points(static_cast<std::size_t>(pattern.point_count()));
  for (std::size_t k = 0; k < found->ids.size(); ++k) {
    points[static_cast<std::size_t>(found->ids[k])] = found->image_points[k];
  }
  return points;
}

Result<DetectedPoints> detect_pattern_points(const cv::Mat& image,
                                             const CalibrationPattern& pattern, int min_corners) {
  assert(!image.empty() && image.depth() == CV_8U);
  if (pattern.kind == PatternKind::kCharuco) {
    return detect_charuco(to_grey(image), pattern, min_corners);
  }
  auto points = detect_pattern(image, pattern);
  if (!points) return points.error();
  DetectedPoints found;
  found.image_points = std::move(*points);
  found.ids.resize(found.image_points.size());
  for (std::size_t k = 0; k < found.ids.size(); ++k) found.ids[k] = static_cast<int>(k);
  return found;
}

}  // namespace telear::vision
