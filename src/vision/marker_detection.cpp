#include "telear/vision/marker_detection.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>
#include <opencv2/aruco.hpp>
#include <opencv2/imgproc.hpp>

#include "grey_sampling.hpp"
#include "telear/vision/mono_calibration.hpp"

namespace telear::vision {
namespace {

double sample(const cv::Mat& grey, const Eigen::Vector2d& p) {
  return bilinear_grey(grey, p.x(), p.y());
}

}  // namespace

std::vector<Eigen::Vector2d> refine_marker_corners(const cv::Mat& grey,
                                                   const std::vector<Eigen::Vector2d>& initial,
                                                   int cells) {
  assert(grey.type() == CV_8UC1 && initial.size() == 4 && cells >= 3 &&
         "refine_marker_corners(): a grey image, 4 corners and at least 3 cells");
  const double side_cells = cells;
  std::vector<Eigen::Vector2d> corners = initial;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (const auto& c : initial) centre += c / 4.0;
  for (int iteration = 0; iteration < 3; ++iteration) {
    std::array<Eigen::Vector3d, 4> lines;  // a x + b y + c = 0, (a, b) unit
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector2d a = corners[k], b = corners[(k + 1) % 4];
      const double length = (b - a).norm();
      if (length < 8.0) return initial;
      const double cell = length / side_cells;
      const Eigen::Vector2d along = (b - a) / length;
      Eigen::Vector2d normal(-along.y(), along.x());
      if (normal.dot(0.5 * (a + b) - centre) < 0) normal = -normal;  // outwards
      // Half a cell across the side, where the quiet zone is narrowest: a marker seen at a
      // slant is foreshortened across some sides, and half a cell along them reached the dark
      // beyond the quiet zone and pulled those sides in (issue 26).
      const double cell_across = 2.0 * normal.dot(a - centre) / side_cells;
      const double reach = 0.5 * std::min(cell, cell_across);
      const int samples = std::max(8, static_cast<int>(2 * length));
      std::vector<Eigen::Vector2d> bases;
      for (int i = 0; i < samples; ++i) {
        bases.push_back(a + (b - a) * (0.15 + 0.7 * (i + 0.5) / samples));
      }
      for (const Eigen::Vector2d& p : bases) {
        for (const double s : {-reach - 1.0, reach + 1.0}) {
          const Eigen::Vector2d q = p + s * normal;
          if (q.x() < 1 || q.y() < 1 || q.x() > grey.cols - 2 || q.y() > grey.rows - 2)
            return initial;
        }
      }
      std::vector<double> dark, light;
      for (const Eigen::Vector2d& p : bases) {
        dark.push_back(sample(grey, p - reach * normal));
        light.push_back(sample(grey, p + reach * normal));
      }
      const double black = median_of(dark), white = median_of(light);
      if (white - black < 20.0) return initial;
      std::vector<Eigen::Vector2d> edge;
      constexpr double kStep = 0.05;
      for (std::size_t i = 0; i < bases.size(); ++i) {
        const Eigen::Vector2d& p = bases[i];
        // Each sample's own half-way level: light falling off along the edge (a plate lit
        // from one side) makes one level for the whole edge cross too far out where the white
        // is darker and too far in where it is lighter, tilting the edge (issue 26 item 1).
        if (light[i] - dark[i] < 0.5 * (white - black)) continue;  // a cell or a shadow in the way
        const double level = 0.5 * (dark[i] + light[i]);
        // The half-level crossing (dark -> light going outwards) nearest to the current line.
        double best = std::numeric_limits<double>::infinity();
        double previous = sample(grey, p - reach * normal);
        for (double s = -reach; s < reach; s += kStep) {
          const double next = sample(grey, p + (s + kStep) * normal);
          if (previous < level && next >= level) {
            const double crossing = s + kStep * (level - previous) / (next - previous);
            if (std::abs(crossing) < std::abs(best)) best = crossing;
          }
          previous = next;
        }
        if (std::isfinite(best)) edge.push_back(p + best * normal);
      }
      if (edge.size() < 5) return initial;
      Eigen::Vector2d mean = Eigen::Vector2d::Zero();
      for (const auto& e : edge) mean += e / static_cast<double>(edge.size());
      Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
      for (const auto& e : edge) scatter += (e - mean) * (e - mean).transpose();
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(scatter);
      const Eigen::Vector2d line_normal = solver.eigenvectors().col(0);  // smallest eigenvalue
      lines[k] = Eigen::Vector3d(line_normal.x(), line_normal.y(), -line_normal.dot(mean));
    }
    for (int k = 0; k < 4; ++k) {
      // Corner k joins side k - 1 (from corner k - 1) and side k (to corner k + 1).
      const Eigen::Vector3d point = lines[(k + 3) % 4].cross(lines[k]);
      if (std::abs(point.z()) < 1e-6) return initial;
      corners[k] = point.head<2>() / point.z();
      if ((corners[k] - initial[k]).norm() > 4.0) return initial;
    }
  }
  return corners;
}

std::vector<Eigen::Vector2d> detect_aruco_marker(const cv::Mat& image, int id,
                                                 const MarkerDetectionOptions& options) {
  assert((image.type() == CV_8UC1 || image.type() == CV_8UC3 || image.type() == CV_8UC4) &&
         "detect_aruco_marker(): an 8-bit grey, RGB or RGBA image");
  cv::Mat grey;
  if (image.type() == CV_8UC1) {
    grey = image;
  } else {
    cv::cvtColor(image, grey, image.type() == CV_8UC4 ? cv::COLOR_RGBA2GRAY : cv::COLOR_RGB2GRAY);
  }
  const cv::Ptr<cv::aruco::Dictionary> dictionary =
      cv::aruco::getPredefinedDictionary(cv::aruco::DICT_4X4_50);
  cv::Ptr<cv::aruco::DetectorParameters> parameters = cv::aruco::DetectorParameters::create();
  parameters->cornerRefinementMethod = cv::aruco::CORNER_REFINE_NONE;
  std::vector<std::vector<cv::Point2f>> corners;
  std::vector<int> ids;
  cv::aruco::detectMarkers(grey, dictionary, corners, ids, parameters);
  std::vector<Eigen::Vector2d> found;
  int matches = 0;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (ids[i] != id) continue;
    ++matches;
    found.clear();
    for (const cv::Point2f& p : corners[i]) found.emplace_back(p.x, p.y);
  }
  if (matches != 1 || found.size() != 4) return {};
  if (!options.refine) return found;
  return refine_marker_corners(grey, found, options.cells);
}

}  // namespace telear::vision
