#include "telear/vision/capture_observations.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <opencv2/imgproc.hpp>

#include "telear/core/number_format.hpp"
#include "telear/vision/marker_detection.hpp"

namespace telear::vision {
namespace {

// Point id -> pixel, one frame's detection.
using FramePoints = std::map<int, Eigen::Vector2d>;

// The mean of the frames' points, point by point (a board's partial views may differ in which
// corners they hold), or empty when none found the target or the frames spread.
std::vector<TargetPixel> average_points(const std::vector<FramePoints>& found, double max_spread_px,
                                        double& spread_px) {
  spread_px = 0.0;
  std::map<int, std::pair<Eigen::Vector2d, int>> sums;
  for (const FramePoints& frame : found) {
    for (const auto& [id, pixel] : frame) {
      auto& [sum, count] = sums.try_emplace(id, Eigen::Vector2d::Zero(), 0).first->second;
      sum += pixel;
      ++count;
    }
  }
  std::vector<TargetPixel> mean;
  for (const auto& [id, sum] : sums) mean.push_back({id, sum.first / sum.second});
  for (const FramePoints& frame : found) {
    for (const TargetPixel& m : mean) {
      const auto it = frame.find(m.point);
      if (it != frame.end()) spread_px = std::max(spread_px, (it->second - m.pixel).norm());
    }
  }
  if (spread_px > max_spread_px) return {};
  return mean;
}

}  // namespace

int min_board_corners(const RegistrationTarget& target) {
  const int corners = static_cast<int>(target.points().size());
  return std::max(4, (corners + 1) / 2);
}

Result<CaptureObservations> detect_capture_targets(const std::string& directory,
                                                   const CaptureSet& capture,
                                                   const core::MarkerMount& marker,
                                                   const CaptureDetectionOptions& options) {
  return detect_capture_targets(directory, capture, registration_target_from_mount(marker),
                                options);
}

Result<std::array<TargetDetection, 2>> detect_in_captured_frame(const std::string& directory,
                                                                const CapturedFrame& frame,
                                                                const RegistrationTarget& target) {
  auto images = read_captured_images(directory, frame);
  if (!images) return images.error();
  TargetDetectionOptions detection;
  detection.min_corners = 1;  // a pose's corners are counted by the caller
  std::array<TargetDetection, 2> seen;
  cv::Mat rgb;
  for (auto [image, found] : {std::pair{&images->left, &seen[0]}, {&images->right, &seen[1]}}) {
    // The folder stores what OpenCV writes (BGR); the detector takes telear's RGB.
    if (image->channels() == 3) {
      cv::cvtColor(*image, rgb, cv::COLOR_BGR2RGB);
    } else {
      rgb = *image;
    }
    *found = detect_registration_target(rgb, target, detection);
  }
  return seen;
}

Result<CaptureObservations> detect_capture_targets(const std::string& directory,
                                                   const CaptureSet& capture,
                                                   const RegistrationTarget& target,
                                                   const CaptureDetectionOptions& options) {
  CaptureObservations out;
  out.target = target;
  out.observations.target_points = target.points();
  const bool board = target.is_board();
  const std::string what = board ? "board" : "marker";
  const int min_corners =
      options.min_corners > 0 ? options.min_corners : (board ? min_board_corners(target) : 0);
  for (std::size_t p = 0; p < capture.poses.size(); ++p) {
    const CapturedPose& pose = capture.poses[p];
    const std::string name = "pose " + std::to_string(p);
    std::vector<FramePoints> left, right;
    for (const CapturedFrame& frame : pose.frames) {
      // Every corner found; the pose's average is checked against min_corners below.
      auto seen = detect_in_captured_frame(directory, frame, target);
      if (!seen) return seen.error();
      for (auto [d, found] : {std::pair{&(*seen)[0], &left}, {&(*seen)[1], &right}}) {
        if (!d->found()) continue;
        FramePoints points;
        for (std::size_t i = 0; i < d->ids.size(); ++i) points[d->ids[i]] = d->pixels[i];
        found->push_back(std::move(points));
      }
    }
    HandEyeView view;
    view.name = name;
    view.q = pose.q;
    const std::size_t frames = pose.frames.size();
    bool seen[2] = {false, false};
    int eye = -1;
    for (auto [label, found, pixels, count] :
         {std::tuple{"left", &left, &view.left, &out.left_found},
          std::tuple{"right", &right, &view.right, &out.right_found}}) {
      ++eye;
      const std::string eye_name = label;
      double spread = 0.0;
      std::vector<TargetPixel> mean = average_points(*found, options.max_frame_spread_px, spread);
      if (found->empty()) {
        if (!board)
          out.notes.push_back(name + ": the marker was not found in the " + eye_name + " eye");
        continue;
      }
      if (mean.empty()) {
        out.notes.push_back(name + ": the " + eye_name + " eye's corners moved by " +
                            core::format_fixed(spread, 2) + " px across its frames (more than " +
                            core::format_fixed(options.max_frame_spread_px, 2) +
                            "): not used; was the arm at rest?");
        continue;
      }
      if (board && static_cast<int>(mean.size()) < min_corners) {
        out.notes.push_back(name + ": the " + eye_name + " eye saw " + std::to_string(mean.size()) +
                            " corners of the board (fewer than " + std::to_string(min_corners) +
                            "): not used");
        continue;
      }
      if (found->size() < frames) {
        out.notes.push_back(name + ": the " + eye_name + " eye found the " + what + " in " +
                            std::to_string(found->size()) + " of " + std::to_string(frames) +
                            " frames");
      }
      *pixels = std::move(mean);
      seen[eye] = true;
      ++*count;
    }
    if (board && seen[0] != seen[1]) {
      out.notes.push_back(name + ": the board was seen in the " + (seen[0] ? "left" : "right") +
                          " eye only");
    } else if (board && !seen[0] && !seen[1]) {
      out.notes.push_back(name + ": the board gave no usable corners in either eye");
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
    std::vector<cv::Point> dots;  // a board's corners
    for (std::size_t v = 0; v < detected.observations.views.size(); ++v) {
      const HandEyeView& view = detected.observations.views[v];
      const auto& pixels = eye == 0 ? view.left : view.right;
      if (pixels.size() < 3) continue;
      std::vector<cv::Point> points, polygon;
      for (const TargetPixel& p : pixels) {
        points.emplace_back(static_cast<int>(std::lround(p.pixel.x())),
                            static_cast<int>(std::lround(p.pixel.y())));
      }
      // A marker's four corners are their own hull; a board's seen corners are scattered.
      cv::convexHull(points, polygon);
      seen.emplace_back(v, std::move(polygon));
      if (pixels.size() > 4) dots.insert(dots.end(), points.begin(), points.end());
    }
    // Translucent fills first, so overlapping markers show brighter, then crisp outlines.
    for (const auto& [v, polygon] : seen) {
      cv::Mat fill = half.clone();
      cv::fillConvexPoly(fill, polygon, cv::Scalar(60, 200, 60), cv::LINE_AA);
      cv::addWeighted(fill, 0.45, half, 0.55, 0.0, half);
    }
    for (const cv::Point& c : dots) {
      cv::circle(half, c, 1, cv::Scalar(255, 255, 255), cv::FILLED, cv::LINE_AA);
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
