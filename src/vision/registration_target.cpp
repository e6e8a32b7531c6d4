#include "telear/vision/registration_target.hpp"

#include <algorithm>
#include <cassert>
#include <cctype>
#include <cmath>
#include <opencv2/aruco.hpp>
#include <opencv2/aruco/charuco.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "telear/core/number_format.hpp"
#include "telear/core/number_list.hpp"
#include "telear/vision/aruco_dictionary.hpp"
#include "telear/vision/charuco_board.hpp"
#include "telear/vision/marker_detection.hpp"

#include "vision_text.hpp"

namespace telear::vision {
namespace {

std::vector<std::string> split_fields(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, separator)) parts.push_back(part);
  if (!text.empty() && text.back() == separator) parts.emplace_back();
  return parts;
}

bool parse_int_into(const std::string& text, int& value) {
  try {
    std::size_t used = 0;
    value = std::stoi(text, &used);
    return used == text.size();
  } catch (const std::exception&) {
    return false;
  }
}

bool parse_positive(const std::string& text, double& value) {
  const Result<double> number = core::parse_number(text, "");
  if (!number || *number <= 0.0) return false;
  value = *number;
  return true;
}

cv::Ptr<cv::aruco::CharucoBoard> charuco_board(const RegistrationTarget& t) {
  return cv::aruco::CharucoBoard::create(t.squares_x, t.squares_y, static_cast<float>(t.square_m),
                                         static_cast<float>(t.marker_m),
                                         predefined_aruco_dictionary(t.dictionary));
}

// OpenCV's board frame (origin at the printed top-left corner, x right, y down, z into the
// board) to the target frame (centre, x right, y up, z out of the face).
Eigen::Vector3d from_board(const RegistrationTarget& t, const cv::Point3f& p) {
  return {p.x - 0.5 * t.squares_x * t.square_m, 0.5 * t.squares_y * t.square_m - p.y, 0.0};
}

cv::Ptr<cv::aruco::DetectorParameters> detector_parameters() {
  cv::Ptr<cv::aruco::DetectorParameters> parameters = cv::aruco::DetectorParameters::create();
  // Corners are refined afterwards (marker edges, or cornerSubPix on a board's squares).
  parameters->cornerRefinementMethod = cv::aruco::CORNER_REFINE_NONE;
  // Markers of a few pixels per cell, as a flange target seen from a rig 2-3 m away: accept
  // small outlines and sample each cell more finely before reading its bit.
  parameters->minMarkerPerimeterRate = 0.01;
  parameters->perspectiveRemovePixelPerCell = 8;
  // The default (0.05 of the perimeter) discards a marker whose one-cell quiet zone is a
  // candidate outline of its own, and OpenCV then keeps the quiet zone's outline (it failed
  // on every AprilTag 36h11 against a grey background); nested outlines of one marker are
  // merged in detected_markers() instead.
  parameters->minMarkerDistanceRate = 0.01;
  return parameters;
}

double perimeter(const std::vector<cv::Point2f>& corners) {
  double sum = 0.0;
  for (std::size_t k = 0; k < corners.size(); ++k) {
    sum += cv::norm(corners[(k + 1) % corners.size()] - corners[k]);
  }
  return sum;
}

cv::Point2f centre_of(const std::vector<cv::Point2f>& corners) {
  cv::Point2f sum(0.f, 0.f);
  for (const cv::Point2f& c : corners) sum += c;
  return sum / static_cast<float>(corners.size());
}

struct DetectedMarkers {
  std::vector<std::vector<cv::Point2f>> corners;
  std::vector<int> ids;
};

// cv::aruco's markers with each id once: outlines of one id nested within each other (their
// centres within a quarter side: the black square and a contour just inside it) are one
// marker, the outer outline kept; an id found at two places is dropped (ambiguous).
DetectedMarkers detected_markers(const cv::Mat& grey,
                                 const cv::Ptr<cv::aruco::Dictionary>& dictionary) {
  std::vector<std::vector<cv::Point2f>> corners;
  std::vector<int> ids;
  cv::aruco::detectMarkers(grey, dictionary, corners, ids, detector_parameters());
  DetectedMarkers out;
  std::vector<bool> done(ids.size(), false);
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (done[i]) continue;
    std::size_t best = i;
    bool ambiguous = false;
    for (std::size_t j = i + 1; j < ids.size(); ++j) {
      if (ids[j] != ids[i]) continue;
      done[j] = true;
      const double side = std::max(perimeter(corners[i]), perimeter(corners[j])) / 4.0;
      if (cv::norm(centre_of(corners[i]) - centre_of(corners[j])) > 0.25 * side) {
        ambiguous = true;
      } else if (perimeter(corners[j]) > perimeter(corners[best])) {
        best = j;
      }
    }
    if (ambiguous) continue;
    out.corners.push_back(corners[best]);
    out.ids.push_back(ids[best]);
  }
  return out;
}

cv::Mat grey_of(const cv::Mat& image) {
  assert((image.type() == CV_8UC1 || image.type() == CV_8UC3 || image.type() == CV_8UC4) &&
         "detect_registration_target(): an 8-bit grey, RGB or RGBA image");
  if (image.type() == CV_8UC1) return image;
  cv::Mat grey;
  cv::cvtColor(image, grey, image.type() == CV_8UC4 ? cv::COLOR_RGBA2GRAY : cv::COLOR_RGB2GRAY);
  return grey;
}

}  // namespace

std::string RegistrationTarget::spec() const {
  switch (kind) {
    case TargetKind::kAruco:
      return "aruco:" + dictionary + ":" + std::to_string(id) + ":" + core::format_number(side_m);
    case TargetKind::kAprilTag:
      return "apriltag:" + dictionary.substr(14) + ":" + std::to_string(id) + ":" +
             core::format_number(side_m);
    case TargetKind::kCharuco:
      return "charuco:" + std::to_string(squares_x) + "x" + std::to_string(squares_y) + ":" +
             core::format_number(square_m) + ":" + core::format_number(marker_m) + ":" + dictionary;
  }
  return {};
}

std::string RegistrationTarget::description() const {
  switch (kind) {
    case TargetKind::kAruco:
      return "ArUco marker " + std::to_string(id) + " (" + dictionary + ", " +
             core::format_number(side_m) + " m)";
    case TargetKind::kAprilTag:
      return "AprilTag " + dictionary.substr(14) + " id " + std::to_string(id) + " (" +
             core::format_number(side_m) + " m)";
    case TargetKind::kCharuco:
      return "ChArUco board " + std::to_string(squares_x) + "x" + std::to_string(squares_y) + " (" +
             core::format_number(square_m) + " m squares, " + dictionary + ")";
  }
  return {};
}

int RegistrationTarget::marker_cells() const {
  return predefined_aruco_dictionary(dictionary)->markerSize + 2;
}

std::vector<Eigen::Vector3d> RegistrationTarget::points() const {
  if (!is_board()) {
    const double h = side_m / 2.0;
    return {{-h, h, 0.0}, {h, h, 0.0}, {h, -h, 0.0}, {-h, -h, 0.0}};
  }
  std::vector<Eigen::Vector3d> out;
  const cv::Ptr<cv::aruco::CharucoBoard> board = charuco_board(*this);
  for (const cv::Point3f& p : board->chessboardCorners) {
    out.push_back(from_board(*this, p));
  }
  return out;
}

Eigen::Vector2d RegistrationTarget::printed_size_m() const {
  if (!is_board()) {
    const double cells = marker_cells();
    return Eigen::Vector2d::Constant(side_m * (cells + 2.0) / cells);
  }
  return {(squares_x + 1) * square_m, (squares_y + 1) * square_m};
}

Result<RegistrationTarget> parse_registration_target(const std::string& spec) {
  const std::vector<std::string> f = split_fields(spec, ':');
  const std::string quoted = "target '" + spec + "': ";
  const std::string kinds =
      "expected aruco:DICT:ID:SIDE_M, apriltag:FAMILY:ID:SIDE_M or "
      "charuco:XxY:SQUARE_M:MARKER_M:DICT (e.g. aruco:4x4_50:0:0.1, apriltag:36h11:3:0.08, "
      "charuco:5x5:0.05:0.038:4x4_50)";
  if (f.empty() || (f[0] != "aruco" && f[0] != "apriltag" && f[0] != "charuco")) {
    return Error{quoted + "unknown kind '" + (f.empty() ? "" : f[0]) + "'; " + kinds};
  }
  RegistrationTarget t;
  if (f[0] == "aruco" || f[0] == "apriltag") {
    const bool april = f[0] == "apriltag";
    t.kind = april ? TargetKind::kAprilTag : TargetKind::kAruco;
    if (f.size() != 4) {
      return Error{quoted + "expected 4 fields " + f[0] + (april ? ":FAMILY" : ":DICT") +
                   ":ID:SIDE_M, got " + std::to_string(f.size())};
    }
    t.dictionary = april ? opencv_apriltag_family(f[1]) : opencv_aruco_dictionary(f[1]);
    if (t.dictionary.empty()) {
      return april ? Error{quoted + "unknown AprilTag family '" + f[1] + "' (expected one of " +
                           opencv_apriltag_family_list() + ")"}
                   : Error{quoted + "unknown ArUco dictionary '" + f[1] + "' (expected one of " +
                           opencv_aruco_dictionary_list() + ")"};
    }
    const int size = aruco_dictionary_size(t.dictionary);
    if (!parse_int_into(f[2], t.id) || t.id < 0 || t.id >= size) {
      return Error{quoted + "id '" + f[2] + "' must be an integer in 0.." +
                   std::to_string(size - 1) + " (" + t.dictionary + ")"};
    }
    if (!parse_positive(f[3], t.side_m)) {
      return Error{quoted + "side '" + f[3] + "' must be a positive number of metres"};
    }
    return t;
  }
  t.kind = TargetKind::kCharuco;
  if (f.size() != 5) {
    return Error{quoted + "expected 5 fields charuco:XxY:SQUARE_M:MARKER_M:DICT, got " +
                 std::to_string(f.size())};
  }
  const std::vector<std::string> squares = split_fields(upper(f[1]), 'X');
  if (squares.size() != 2 || !parse_int_into(squares[0], t.squares_x) ||
      !parse_int_into(squares[1], t.squares_y) || t.squares_x < 2 || t.squares_y < 2 ||
      t.squares_x > 100 || t.squares_y > 100) {
    return Error{quoted + "squares '" + f[1] + "' must be XxY with X and Y in 2..100 (e.g. 5x5)"};
  }
  if (!parse_positive(f[2], t.square_m)) {
    return Error{quoted + "square side '" + f[2] + "' must be a positive number of metres"};
  }
  if (!parse_positive(f[3], t.marker_m)) {
    return Error{quoted + "marker side '" + f[3] + "' must be a positive number of metres"};
  }
  if (t.marker_m >= t.square_m) {
    return Error{quoted + "marker side " + core::format_number(t.marker_m) +
                 " m must be smaller than the square side " + core::format_number(t.square_m) +
                 " m (the marker sits inside a white square)"};
  }
  t.dictionary = opencv_aruco_dictionary(f[4]);
  if (t.dictionary.empty()) {
    return Error{quoted + "unknown ArUco dictionary '" + f[4] + "' (expected one of " +
                 opencv_aruco_dictionary_list() + ")"};
  }
  const int markers = charuco_marker_count(t.squares_x, t.squares_y);
  const int size = aruco_dictionary_size(t.dictionary);
  if (markers > size) {
    return Error{quoted + "a " + f[1] + " board has " + std::to_string(markers) + " markers but " +
                 t.dictionary + " holds " + std::to_string(size) + ": choose a larger dictionary"};
  }
  return t;
}

RegistrationTarget registration_target_from_mount(const core::MarkerMount& mount) {
  RegistrationTarget t;
  t.kind = TargetKind::kAruco;
  t.dictionary = opencv_aruco_dictionary(mount.dictionary);
  if (t.dictionary.empty()) t.dictionary = "DICT_4X4_50";  // the mount file's only one
  t.id = mount.id;
  t.side_m = mount.side_m;
  return t;
}

TargetDetection detect_registration_target(const cv::Mat& image, const RegistrationTarget& target,
                                           const TargetDetectionOptions& options) {
  TargetDetection out;
  if (target.kind == TargetKind::kAruco && target.dictionary == "DICT_4X4_50") {
    // The robot's marker: exactly as detect_aruco_marker finds it (the registration figures
    // in docs/registration.md were measured that way).
    MarkerDetectionOptions marker;
    marker.refine = options.refine;
    marker.cells = target.marker_cells();
    const std::vector<Eigen::Vector2d> corners = detect_aruco_marker(image, target.id, marker);
    if (corners.size() != 4) return out;
    out.markers_found = 1;
    for (int k = 0; k < 4; ++k) {
      out.ids.push_back(k);
      out.pixels.push_back(corners[k]);
    }
    return out;
  }
  const cv::Mat grey = grey_of(image);
  const cv::Ptr<cv::aruco::Dictionary> dictionary = predefined_aruco_dictionary(target.dictionary);
  const DetectedMarkers markers = detected_markers(grey, dictionary);
  const auto& corners = markers.corners;
  const auto& ids = markers.ids;
  if (!target.is_board()) {
    std::vector<Eigen::Vector2d> found;
    for (std::size_t i = 0; i < ids.size(); ++i) {
      if (ids[i] != target.id) continue;
      for (const cv::Point2f& p : corners[i]) found.emplace_back(p.x, p.y);
    }
    if (found.size() != 4) return out;
    out.markers_found = 1;
    if (options.refine) found = refine_marker_corners(grey, found, target.marker_cells());
    for (int k = 0; k < 4; ++k) {
      out.ids.push_back(k);
      out.pixels.push_back(found[k]);
    }
    return out;
  }
  const cv::Ptr<cv::aruco::CharucoBoard> board = charuco_board(target);
  // Only the board's own markers (another board or marker in view would confuse it).
  std::vector<std::vector<cv::Point2f>> board_corners;
  std::vector<int> board_ids;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (std::find(board->ids.begin(), board->ids.end(), ids[i]) == board->ids.end()) continue;
    board_corners.push_back(corners[i]);
    board_ids.push_back(ids[i]);
  }
  out.markers_found = static_cast<int>(board_ids.size());
  if (board_ids.empty()) return out;
  std::vector<cv::Point2f> charuco_corners;
  std::vector<int> charuco_ids;
  cv::aruco::interpolateCornersCharuco(board_corners, board_ids, grey, board, charuco_corners,
                                       charuco_ids);
  refine_charuco_corners(grey, target.squares_x, target.marker_m / target.square_m, charuco_ids,
                         charuco_corners);
  out.corners_seen = static_cast<int>(charuco_ids.size());
  if (out.corners_seen < std::max(options.min_corners, 1)) return out;
  std::vector<std::size_t> order(charuco_ids.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return charuco_ids[a] < charuco_ids[b]; });
  for (const std::size_t i : order) {
    out.ids.push_back(charuco_ids[i]);
    out.pixels.emplace_back(charuco_corners[i].x, charuco_corners[i].y);
  }
  return out;
}

std::vector<std::array<Eigen::Vector3d, 4>> registration_target_dark_quads(
    const RegistrationTarget& target) {
  std::vector<std::array<Eigen::Vector3d, 4>> quads;
  const cv::Ptr<cv::aruco::Dictionary> dictionary = predefined_aruco_dictionary(target.dictionary);
  const int cells = dictionary->markerSize + 2;
  // One marker's black cells, bilinear between its corners c (printed order).
  const auto add_marker = [&](int id, const std::array<Eigen::Vector3d, 4>& c) {
    cv::Mat bits;
    cv::aruco::drawMarker(dictionary, id, cells, bits, 1);
    const auto at = [&](double u, double v) {
      return Eigen::Vector3d(c[0] + u * (c[1] - c[0]) + v * (c[3] - c[0]));
    };
    for (int row = 0; row < cells; ++row) {
      for (int col = 0; col < cells; ++col) {
        if (bits.at<std::uint8_t>(row, col) >= 128) continue;
        const double u0 = static_cast<double>(col) / cells,
                     u1 = static_cast<double>(col + 1) / cells;
        const double v0 = static_cast<double>(row) / cells,
                     v1 = static_cast<double>(row + 1) / cells;
        quads.push_back({at(u0, v0), at(u1, v0), at(u1, v1), at(u0, v1)});
      }
    }
  };
  if (!target.is_board()) {
    const std::vector<Eigen::Vector3d> p = target.points();
    add_marker(target.id, {p[0], p[1], p[2], p[3]});
    return quads;
  }
  const cv::Ptr<cv::aruco::CharucoBoard> board = charuco_board(target);
  for (std::size_t m = 0; m < board->ids.size(); ++m) {
    const auto& o = board->objPoints[m];
    add_marker(board->ids[m], {from_board(target, o[0]), from_board(target, o[1]),
                               from_board(target, o[2]), from_board(target, o[3])});
  }
  // Black squares: those without a marker (cv::aruco puts markers where row and column
  // parities differ, so the printed top-left square is black).
  const double s = target.square_m;
  for (int j = 0; j < target.squares_y; ++j) {
    for (int i = 0; i < target.squares_x; ++i) {
      if (i % 2 != j % 2) continue;
      const cv::Point3f tl(static_cast<float>(i * s), static_cast<float>(j * s), 0.f);
      const cv::Point3f br(static_cast<float>((i + 1) * s), static_cast<float>((j + 1) * s), 0.f);
      quads.push_back({from_board(target, tl), from_board(target, {br.x, tl.y, 0.f}),
                       from_board(target, br), from_board(target, {tl.x, br.y, 0.f})});
    }
  }
  return quads;
}

cv::Mat registration_target_image(const RegistrationTarget& target, double pixels_per_m) {
  const Eigen::Vector2d size = target.printed_size_m();
  const int width = static_cast<int>(std::lround(size.x() * pixels_per_m));
  const int height = static_cast<int>(std::lround(size.y() * pixels_per_m));
  cv::Mat image(height, width, CV_8UC1, cv::Scalar(255));
  // Every dark quad is an axis-aligned rectangle of the print: a pixel is dark when its
  // centre lies inside (print coordinates, pixel i covering [i, i + 1)).
  const auto first_pixel = [](double edge) { return static_cast<int>(std::ceil(edge - 0.5)); };
  for (const auto& quad : registration_target_dark_quads(target)) {
    double x0 = quad[0].x(), x1 = quad[0].x(), y0 = quad[0].y(), y1 = quad[0].y();
    for (const Eigen::Vector3d& p : quad) {
      x0 = std::min(x0, p.x());
      x1 = std::max(x1, p.x());
      y0 = std::min(y0, p.y());
      y1 = std::max(y1, p.y());
    }
    const int left = first_pixel((x0 + 0.5 * size.x()) * pixels_per_m);
    const int right = first_pixel((x1 + 0.5 * size.x()) * pixels_per_m);
    const int top = first_pixel((0.5 * size.y() - y1) * pixels_per_m);
    const int bottom = first_pixel((0.5 * size.y() - y0) * pixels_per_m);
    const cv::Rect rect =
        cv::Rect(left, top, right - left, bottom - top) & cv::Rect(0, 0, width, height);
    if (rect.area() > 0) image(rect) = cv::Scalar(0);
  }
  return image;
}

}  // namespace telear::vision
