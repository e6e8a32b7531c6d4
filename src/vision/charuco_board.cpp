#include "telear/vision/charuco_board.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <opencv2/aruco.hpp>
#include <opencv2/aruco/charuco.hpp>
#include <opencv2/imgproc.hpp>
#include <set>

namespace telear::vision {
namespace {

cv::Ptr<cv::aruco::CharucoBoard> make_board(const CalibrationPattern& pattern) {
  assert(pattern.kind == PatternKind::kCharuco);
  return cv::aruco::CharucoBoard::create(
      pattern.squares_x(), pattern.squares_y(), static_cast<float>(pattern.spacing),
      static_cast<float>(pattern.marker), predefined_aruco_dictionary(pattern.dictionary));
}

// The cornerSubPix half-window for ChArUco corners: the window must stay inside the white
// margin between the corner and the markers of its two white squares, (s - m) / 2 of a
// square s, or their edges pull the corner off (a chessboard's 0.3 s does). So: 0.8 x that
// fraction of the smallest distance between corners that are row or column neighbours on the
// board (the smallest square side in the image), 2 .. 15 px.
int charuco_half_window(const std::vector<cv::Point2f>& points, const std::vector<int>& ids,
                        const CalibrationPattern& pattern) {
  const int cols = pattern.cols;
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t a = 0; a < ids.size(); ++a) {
    for (std::size_t b = a + 1; b < ids.size(); ++b) {
      const int d = std::abs(ids[a] - ids[b]);
      const bool row_neighbours = d == 1 && ids[a] / cols == ids[b] / cols;
      if (row_neighbours || d == cols) nearest = std::min(nearest, cv::norm(points[a] - points[b]));
    }
  }
  if (!std::isfinite(nearest)) return 2;
  const double margin = (pattern.spacing - pattern.marker) / (2.0 * pattern.spacing);
  return std::clamp(static_cast<int>(std::lround(0.8 * margin * nearest)), 2, 15);
}

std::string count_text(std::size_t n, const char* what) {
  return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
}

}  // namespace

int charuco_marker_count(int squares_x, int squares_y) {
  return squares_x * squares_y / 2;
}

bool CharucoLayout::black_square(int i, int j) const {
  return marker_of_square[static_cast<std::size_t>(j * squares_x + i)] < 0;
}

double CharucoLayout::reflectance(double x, double y) const {
  const double i_real = std::floor(x / square), j_real = std::floor(y / square);
  if (i_real < 0 || j_real < 0 || i_real >= squares_x || j_real >= squares_y) return 1.0;
  const int i = static_cast<int>(i_real), j = static_cast<int>(j_real);
  const int index = marker_of_square[static_cast<std::size_t>(j * squares_x + i)];
  if (index < 0) return 0.0;
  const CharucoMarker& marker = markers[static_cast<std::size_t>(index)];
  const double u = (x - marker.top_left.x) / marker.side, v = (y - marker.top_left.y) / marker.side;
  if (u < 0.0 || v < 0.0 || u >= 1.0 || v >= 1.0) return 1.0;  // the white around the marker
  const int n = marker.cells.rows;
  return marker.cells.at<std::uint8_t>(static_cast<int>(v * n), static_cast<int>(u * n)) > 127
             ? 1.0
             : 0.0;
}

CharucoLayout charuco_layout(const CalibrationPattern& pattern) {
  const cv::Ptr<cv::aruco::CharucoBoard> board = make_board(pattern);
  CharucoLayout layout;
  layout.squares_x = pattern.squares_x();
  layout.squares_y = pattern.squares_y();
  layout.square = pattern.spacing;
  layout.marker_of_square.assign(static_cast<std::size_t>(layout.squares_x * layout.squares_y), -1);
  const int cells = board->dictionary->markerSize + 2;
  for (std::size_t k = 0; k < board->ids.size(); ++k) {
    // Take the layout from the board itself, so that it is what the detector assumes.
    const std::vector<cv::Point3f>& corners = board->objPoints[k];
    CharucoMarker marker;
    marker.id = board->ids[k];
    marker.top_left = {std::min({corners[0].x, corners[1].x, corners[2].x, corners[3].x}),
                       std::min({corners[0].y, corners[1].y, corners[2].y, corners[3].y})};
    marker.side = pattern.marker;
    cv::aruco::drawMarker(board->dictionary, marker.id, cells, marker.cells, 1);
    const double cx = marker.top_left.x + 0.5 * marker.side;
    const double cy = marker.top_left.y + 0.5 * marker.side;
    const int i = static_cast<int>(std::floor(cx / pattern.spacing));
    const int j = static_cast<int>(std::floor(cy / pattern.spacing));
    layout.marker_of_square[static_cast<std::size_t>(j * layout.squares_x + i)] =
        static_cast<int>(layout.markers.size());
    layout.markers.push_back(std::move(marker));
  }
  return layout;
}

cv::Mat draw_charuco_board(const CalibrationPattern& pattern, int pixels_per_square,
                           int margin_px) {
  const cv::Ptr<cv::aruco::CharucoBoard> board = make_board(pattern);
  cv::Mat image;
  board->draw(cv::Size(pattern.squares_x() * pixels_per_square + 2 * margin_px,
                       pattern.squares_y() * pixels_per_square + 2 * margin_px),
              image, margin_px, 1);
  return image;
}

Result<DetectedPoints> detect_charuco(const cv::Mat& grey, const CalibrationPattern& pattern,
                                      int min_corners) {
  assert(grey.type() == CV_8UC1);
  const cv::Ptr<cv::aruco::CharucoBoard> board = make_board(pattern);
  const cv::Ptr<cv::aruco::DetectorParameters> parameters = cv::aruco::DetectorParameters::create();
  std::vector<std::vector<cv::Point2f>> corners, rejected;
  std::vector<int> ids;
  cv::aruco::detectMarkers(grey, board->dictionary, corners, ids, parameters, rejected);
  if (!ids.empty()) {
    cv::aruco::refineDetectedMarkers(grey, board, corners, ids, rejected);
  }
  // Markers of the dictionary that are not on this board (another board in view, or a spec
  // with fewer squares than the board) would be placed wrongly: leave them out.
  const int on_board = static_cast<int>(board->ids.size());
  std::size_t kept = 0;
  for (std::size_t k = 0; k < ids.size(); ++k) {
    if (ids[k] < 0 || ids[k] >= on_board) continue;
    ids[kept] = ids[k];
    corners[kept] = corners[k];
    ++kept;
  }
  ids.resize(kept);
  corners.resize(kept);
  if (ids.empty()) {
    return Error{"no ChArUco marker found (dictionary " + pattern.dictionary +
                 "; check that the board was printed for " + pattern.spec() + ")"};
  }

  DetectedPoints found;
  cv::aruco::interpolateCornersCharuco(corners, ids, grey, board, found.image_points, found.ids);
  if (!found.ids.empty()) {
    // OpenCV 4.6 refines the interpolated corners only to 0.1 px (its detector parameters'
    // default accuracy), and on OpenCV's own board image they come out half a pixel off the
    // true corners in x and y: refine them again as telear refines chessboard corners, which
    // puts them within 0.05 px (tests/vision/charuco_pattern_test.cpp).
    const int half = charuco_half_window(found.image_points, found.ids, pattern);
    cv::cornerSubPix(grey, found.image_points, cv::Size(half, half), cv::Size(-1, -1),
                     cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 50, 1e-3));
  }
  const std::string seen = count_text(found.ids.size(), "ChArUco corner") + " (from " +
                           count_text(ids.size(), "marker") + ")";
  if (static_cast<int>(found.ids.size()) < min_corners) {
    return Error{"only " + seen + " found, fewer than the " + std::to_string(min_corners) +
                 " a view needs; show more of the board"};
  }
  std::set<int> rows, cols;
  for (int id : found.ids) {
    rows.insert(id / pattern.cols);
    cols.insert(id % pattern.cols);
  }
  if (rows.size() < 2 || cols.size() < 2) {
    return Error{seen + " found, all on one " + (rows.size() < 2 ? "row" : "column") +
                 " of the board (no homography from a line); show more of the board"};
  }
  return found;
}

}  // namespace telear::vision
