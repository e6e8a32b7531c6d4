#include "telear/vision/charuco_board.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>
#include <opencv2/aruco.hpp>
#include <opencv2/aruco/charuco.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <set>

#include "bent_edge.hpp"
#include "grey_sampling.hpp"
#include "telear/vision/mono_calibration.hpp"

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

double grey_at(const cv::Mat& grey, const cv::Point2d& p) {
  return bilinear_grey(grey, p.x, p.y);
}

cv::Point2d charuco_apply(const cv::Matx33d& H, const cv::Point2d& q) {
  const cv::Vec3d r = H * cv::Vec3d(q.x, q.y, 1.0);
  return {r[0] / r[2], r[1] / r[2]};
}

bool charuco_inside(const cv::Mat& grey, const cv::Point2d& p) {
  return p.x >= 1.0 && p.y >= 1.0 && p.x <= grey.cols - 2.0 && p.y <= grey.rows - 2.0;
}

// Edge points of one half of a board line: from board point c (square units, y down) along
// unit axis u by side (+-1), the black square on the `black_dir` side of it. `to_image` maps
// board points to the image around the current corner estimate. Appends the points found and
// returns their share of the points looked for; -1 when the edge cannot be measured (too near
// the image border, too little contrast).
template <typename ToImage>
double charuco_half_edge(const cv::Mat& grey, const ToImage& to_image, const cv::Point2d& c,
                         const cv::Point2d& u, double side, const cv::Point2d& black_dir,
                         double margin, std::vector<cv::Point2d>& edge) {
  const cv::Point2d start = to_image(c), end = to_image(c + side * u);
  const double length_px = cv::norm(end - start);
  const int samples = std::max(6, static_cast<int>(1.4 * length_px));
  struct Base {
    cv::Point2d point, normal;  // normal: from the black square towards the white margin
    double into_black, into_white;
  };
  std::vector<Base> bases;
  for (int i = 0; i < samples; ++i) {
    const cv::Point2d q = c + side * (0.15 + 0.7 * (i + 0.5) / samples) * u;
    Base base;
    base.point = to_image(q);
    const cv::Point2d white_point = to_image(q - margin * black_dir);
    base.into_white = cv::norm(white_point - base.point);
    base.into_black = cv::norm(to_image(q + 0.4 * black_dir) - base.point);
    if (base.into_white < 1e-6) return -1.0;
    base.normal = (white_point - base.point) / base.into_white;
    if (!charuco_inside(grey, base.point - (base.into_black + 1.0) * base.normal) ||
        !charuco_inside(grey, base.point + (base.into_white + 1.0) * base.normal)) {
      return -1.0;
    }
    bases.push_back(base);
  }
  // The levels: the black square's inside, and the white margin's brightest.
  constexpr double kStep = 0.05;
  std::vector<double> dark, light;
  for (const Base& b : bases) {
    dark.push_back(grey_at(grey, b.point - 0.75 * b.into_black * b.normal));
    double brightest = 0.0;
    for (double s = -0.5 * b.into_black; s <= b.into_white; s += kStep) {
      brightest = std::max(brightest, grey_at(grey, b.point + s * b.normal));
    }
    light.push_back(brightest);
  }
  const double black = median_of(dark), white = median_of(light);
  if (white - black < 20.0) return -1.0;
  const double level = 0.5 * (black + white);
  int found = 0;
  for (const Base& b : bases) {
    // The dark -> light crossing nearest to the current line, from inside the black square to
    // the far side of the white margin (beyond it the marker's black border only darkens).
    double best = std::numeric_limits<double>::infinity();
    double previous = grey_at(grey, b.point - b.into_black * b.normal);
    for (double s = -b.into_black; s < b.into_white; s += kStep) {
      const double next = grey_at(grey, b.point + (s + kStep) * b.normal);
      if (previous < level && next >= level) {
        const double crossing = s + kStep * (level - previous) / (next - previous);
        if (std::abs(crossing) < std::abs(best)) best = crossing;
      }
      previous = next;
    }
    if (std::isfinite(best)) {
      edge.push_back(b.point + best * b.normal);
      ++found;
    }
  }
  return static_cast<double>(found) / static_cast<double>(bases.size());
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

void refine_charuco_corners(const cv::Mat& grey, int squares_x, double marker_ratio,
                            std::vector<int>& ids, std::vector<cv::Point2f>& corners) {
  assert(grey.type() == CV_8UC1 && ids.size() == corners.size() && squares_x >= 2 &&
         marker_ratio > 0.0 && marker_ratio < 1.0 &&
         "refine_charuco_corners(): a grey image, an id per corner, a valid board");
  // (1) cv::aruco's +(0.5, 0.5).
  for (cv::Point2f& corner : corners) corner -= cv::Point2f(0.5f, 0.5f);
  if (corners.size() < 4) return;
  // Board points in squares (x right, y down, the board's top-left outer corner at 0): corner
  // id k at ((k mod (X - 1)) + 1, (k div (X - 1)) + 1); square (i, j) is black when i + j is
  // even (the top-left one is).
  const int per_row = squares_x - 1;
  std::vector<cv::Point2f> board;
  for (const int id : ids) {
    board.emplace_back(static_cast<float>(id % per_row + 1), static_cast<float>(id / per_row + 1));
  }
  const cv::Mat H_found = cv::findHomography(board, corners);
  if (H_found.empty()) return;  // the corners on a line
  const cv::Matx33d H(H_found);
  const double margin = 0.5 * (1.0 - marker_ratio);  // in squares
  const auto black_square = [](int i, int j) { return ((i + j) % 2 + 2) % 2 == 0; };
  enum class Outcome { kRefined, kUnmeasured, kHidden };
  std::vector<Outcome> outcomes(corners.size(), Outcome::kRefined);
  // Each refined corner's edge points of its last pass, per axis, and the image direction of
  // the board's v axis there (which orients the edges' normals alike).
  struct Edges {
    std::vector<cv::Point2d> points[2];
    cv::Point2d towards[2];
  };
  std::vector<Edges> edges(corners.size());
  std::vector<cv::Point2d> refined(corners.size());
  for (std::size_t k = 0; k < corners.size(); ++k) {
    const cv::Point2d c(board[k].x, board[k].y);
    const cv::Point2d initial(corners[k].x, corners[k].y);
    const cv::Point2d c_image = charuco_apply(H, c);
    const double square_px = cv::norm(charuco_apply(H, c + cv::Point2d(1.0, 0.0)) - c_image);
    cv::Point2d p = initial;
    Outcome& outcome = outcomes[k];
    for (int pass = 0; pass < 3 && outcome == Outcome::kRefined; ++pass) {
      const auto to_image = [&](const cv::Point2d& q) { return charuco_apply(H, q) - c_image + p; };
      cv::Vec3d lines[2];
      for (int axis = 0; axis < 2 && outcome == Outcome::kRefined; ++axis) {
        const cv::Point2d u = axis == 0 ? cv::Point2d(1.0, 0.0) : cv::Point2d(0.0, 1.0);
        const cv::Point2d v(u.y, u.x);
        std::vector<cv::Point2d> edge;
        for (const double side : {-1.0, 1.0}) {
          // The square on the +v side of this half of the line.
          const cv::Point2d plus = c + 0.5 * side * u + 0.5 * v;
          const bool black_plus = black_square(static_cast<int>(std::floor(plus.x)),
                                               static_cast<int>(std::floor(plus.y)));
          const double share =
              charuco_half_edge(grey, to_image, c, u, side, black_plus ? v : -v, margin, edge);
          if (share < 0.0) {
            outcome = Outcome::kUnmeasured;
          } else if (share < 0.5) {
            outcome = Outcome::kHidden;
          }
          if (outcome != Outcome::kRefined) break;
        }
        if (outcome != Outcome::kRefined) break;
        // Once more without the points off the line; most of them must be on it, else
        // something covers the edge (the gripper in front of the board).
        const cv::Vec3d line = fit_edge_line(edge);
        std::vector<cv::Point2d> kept;
        for (const cv::Point2d& q : edge) {
          if (std::abs(line[0] * q.x + line[1] * q.y + line[2]) < 0.5) kept.push_back(q);
        }
        if (kept.size() < 0.8 * static_cast<double>(edge.size())) {
          outcome = Outcome::kHidden;
          break;
        }
        lines[axis] = fit_edge_line(kept);
        edges[k].towards[axis] = to_image(c + v) - p;
        edges[k].points[axis] = std::move(kept);
      }
      if (outcome != Outcome::kRefined) break;
      const cv::Vec3d crossing = lines[0].cross(lines[1]);
      if (std::abs(crossing[2]) < 1e-9) {
        outcome = Outcome::kUnmeasured;
        break;
      }
      p = cv::Point2d(crossing[0] / crossing[2], crossing[1] / crossing[2]);
      if (cv::norm(p - initial) > 0.25 * square_px) outcome = Outcome::kHidden;
    }
    refined[k] = p;
  }
  // A lens bends the board's lines (bent_edge.hpp): each edge is taken as a parabola and its
  // tangent at the corner kept. One parabola per edge would triple the corner's variance (its
  // vertex and its bend trade off); the board is small against the lens, so its edges of one
  // axis bend alike: the median bend of each axis' edges is used for all of them.
  double bend[2] = {0.0, 0.0};
  for (int axis = 0; axis < 2; ++axis) {
    std::vector<double> bends;
    for (std::size_t k = 0; k < corners.size(); ++k) {
      if (outcomes[k] != Outcome::kRefined) continue;
      if (auto c = edge_bend(edges[k].points[axis], refined[k], edges[k].towards[axis]))
        bends.push_back(*c);
    }
    if (!bends.empty()) bend[axis] = median_of(bends);
  }
  for (std::size_t k = 0; k < corners.size(); ++k) {
    if (outcomes[k] != Outcome::kRefined) continue;
    cv::Point2d p = refined[k];
    for (int pass = 0; pass < 2; ++pass) {
      cv::Vec3d lines[2];
      for (int axis = 0; axis < 2; ++axis) {
        lines[axis] = edge_tangent(edges[k].points[axis], p, edges[k].towards[axis], bend[axis]);
      }
      const cv::Vec3d crossing = lines[0].cross(lines[1]);
      if (std::abs(crossing[2]) < 1e-9) break;
      p = cv::Point2d(crossing[0] / crossing[2], crossing[1] / crossing[2]);
    }
    corners[k] = cv::Point2f(static_cast<float>(p.x), static_cast<float>(p.y));
  }
  std::size_t kept = 0;
  for (std::size_t k = 0; k < corners.size(); ++k) {
    if (outcomes[k] == Outcome::kHidden) continue;
    ids[kept] = ids[k];
    corners[kept] = corners[k];
    ++kept;
  }
  ids.resize(kept);
  corners.resize(kept);
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
