#include "telear/vision/capture_observations.hpp"

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "telear/core/number_format.hpp"
#include "telear/vision/marker_detection.hpp"

namespace telear::vision {
namespace {

// The mean of the frames' corners, or empty when none found the marker or they spread.
std::vector<Eigen::Vector2d> average_corners(const std::vector<std::vector<Eigen::Vector2d>>& found,
                                             double max_spread_px, double& spread_px) {
  spread_px = 0.0;
  if (found.empty()) return {};
  std::vector<Eigen::Vector2d> mean(4, Eigen::Vector2d::Zero());
  for (const auto& corners : found) {
    for (std::size_t k = 0; k < 4; ++k) mean[k] += corners[k];
  }
  for (auto& m : mean) m /= static_cast<double>(found.size());
  for (const auto& corners : found) {
    for (std::size_t k = 0; k < 4; ++k)
      spread_px = std::max(spread_px, (corners[k] - mean[k]).norm());
  }
  if (spread_px > max_spread_px) return {};
  return mean;
}

}  // namespace

std::vector<Eigen::Vector3d> marker_target_points(const core::MarkerMount& marker) {
  const double h = marker.side_m / 2.0;
  return {{-h, h, 0.0}, {h, h, 0.0}, {h, -h, 0.0}, {-h, -h, 0.0}};
}

Result<CaptureObservations> detect_capture_targets(const std::string& directory,
                                                   const CaptureSet& capture,
                                                   const core::MarkerMount& marker,
                                                   const CaptureDetectionOptions& options) {
  CaptureObservations out;
  out.observations.target_points = marker_target_points(marker);
  for (std::size_t p = 0; p < capture.poses.size(); ++p) {
    const CapturedPose& pose = capture.poses[p];
    const std::string name = "pose " + std::to_string(p);
    std::vector<std::vector<Eigen::Vector2d>> left, right;
    for (const CapturedFrame& frame : pose.frames) {
      auto images = read_captured_images(directory, frame);
      if (!images) return images.error();
      // The folder stores what OpenCV writes (BGR); the detector takes telear's RGB.
      cv::Mat rgb;
      for (auto [image, found] : {std::pair{&images->left, &left}, {&images->right, &right}}) {
        if (image->channels() == 3) {
          cv::cvtColor(*image, rgb, cv::COLOR_BGR2RGB);
        } else {
          rgb = *image;
        }
        std::vector<Eigen::Vector2d> corners = detect_aruco_marker(rgb, marker.id);
        if (!corners.empty()) found->push_back(std::move(corners));
      }
    }
    HandEyeView view;
    view.name = name;
    view.q = pose.q;
    const std::size_t frames = pose.frames.size();
    for (auto [eye, found, pixels, count] :
         {std::tuple{"left", &left, &view.left, &out.left_found},
          std::tuple{"right", &right, &view.right, &out.right_found}}) {
      double spread = 0.0;
      const std::vector<Eigen::Vector2d> mean =
          average_corners(*found, options.max_frame_spread_px, spread);
      if (found->empty()) {
        out.notes.push_back(name + ": the marker was not found in the " + eye + " eye");
        continue;
      }
      if (mean.empty()) {
        out.notes.push_back(name + ": the " + std::string(eye) + " eye's corners moved by " +
                            core::format_fixed(spread, 2) + " px across its frames (more than " +
                            core::format_fixed(options.max_frame_spread_px, 2) +
                            "): not used; was the arm at rest?");
        continue;
      }
      if (found->size() < frames) {
        out.notes.push_back(name + ": the " + std::string(eye) + " eye found the marker in " +
                            std::to_string(found->size()) + " of " + std::to_string(frames) +
                            " frames");
      }
      for (std::size_t k = 0; k < mean.size(); ++k) {
        pixels->push_back({static_cast<int>(k), mean[k]});
      }
      ++*count;
    }
    out.observations.views.push_back(std::move(view));
  }
  return out;
}

cv::Mat coverage_image(const CaptureObservations& detected, int width, int height) {
  cv::Mat out(height, 2 * width, CV_8UC3, cv::Scalar(40, 40, 40));
  for (int eye = 0; eye < 2; ++eye) {
    cv::Mat half = out(cv::Rect(eye * width, 0, width, height));
    std::vector<std::pair<std::size_t, std::vector<cv::Point>>> seen;
    for (std::size_t v = 0; v < detected.observations.views.size(); ++v) {
      const HandEyeView& view = detected.observations.views[v];
      const auto& pixels = eye == 0 ? view.left : view.right;
      if (pixels.size() < 3) continue;
      std::vector<cv::Point> polygon;
      for (const TargetPixel& p : pixels) {
        polygon.emplace_back(static_cast<int>(std::lround(p.pixel.x())),
                             static_cast<int>(std::lround(p.pixel.y())));
      }
      seen.emplace_back(v, std::move(polygon));
    }
    // Translucent fills first, so overlapping markers show brighter, then crisp outlines.
    for (const auto& [v, polygon] : seen) {
      cv::Mat fill = half.clone();
      cv::fillConvexPoly(fill, polygon, cv::Scalar(60, 200, 60), cv::LINE_AA);
      cv::addWeighted(fill, 0.45, half, 0.55, 0.0, half);
    }
    for (const auto& [v, polygon] : seen) {
      cv::polylines(half, polygon, true, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
      cv::putText(half, std::to_string(v), polygon.front() + cv::Point(2, -3),
                  cv::FONT_HERSHEY_SIMPLEX, 0.35, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
    }
    cv::putText(half, eye == 0 ? "left" : "right", cv::Point(8, 20), cv::FONT_HERSHEY_SIMPLEX, 0.6,
                cv::Scalar(220, 220, 220), 1, cv::LINE_AA);
  }
  cv::line(out, cv::Point(width, 0), cv::Point(width, height - 1), cv::Scalar(128, 128, 128));
  return out;
}

}  // namespace telear::vision
