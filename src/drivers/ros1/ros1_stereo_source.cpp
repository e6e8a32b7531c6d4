#include "telear/drivers/ros1_stereo_source.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>
#include <utility>
#include <vector>

#include "drivers/ros1/camera_info_calibration.hpp"
#include "drivers/ros1/ros1_camera_link.hpp"
#include "telear/core/clock.hpp"

namespace telear::drivers {
namespace {

std::string seconds_text(double seconds) {
  char text[32];
  std::snprintf(text, sizeof text, "%g s", seconds);
  return text;
}

std::string ms_text(double ms) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f ms", ms);
  return text;
}

std::chrono::nanoseconds ns(std::int64_t value) {
  return std::chrono::nanoseconds(std::max<std::int64_t>(value, 0));
}

// The pairing error (left stamp minus right stamp) over a span of pairs.
struct PairingFigures {
  std::uint64_t pairs = 0;
  double sum_abs_ms = 0.0, max_abs_ms = 0.0;

  void add(std::int64_t error_ns) {
    const double ms = std::abs(static_cast<double>(error_ns)) * 1e-6;
    ++pairs;
    sum_abs_ms += ms;
    max_abs_ms = std::max(max_abs_ms, ms);
  }
  std::string text() const {
    char text[96];
    std::snprintf(text, sizeof text, "pairing error mean %.2f ms, max %.2f ms",
                  pairs ? sum_abs_ms / static_cast<double>(pairs) : 0.0, max_abs_ms);
    return text;
  }
};

// Why no pair came between `before` and `now` (two health snapshots `span` apart, e.g.
// "for 2 s"): the master, a topic without messages, messages that cannot be converted, or
// stamps further apart than the tolerance.
std::string why_no_pairs(const ros1::CameraLinkHealth& now, const ros1::CameraLinkHealth& before,
                         const Ros1StereoSourceOptions& options, const std::string& span) {
  if (!now.master) return "the ROS master at " + now.master_uri + " does not answer " + span;
  const ros1::EyeHealth* eyes[2][2] = {{&now.left, &before.left}, {&now.right, &before.right}};
  const std::string topics[2] = {options.left_topic, options.right_topic};
  std::string silent, unusable;
  for (int eye = 0; eye < 2; ++eye) {
    const ros1::EyeHealth& e = *eyes[eye][0];
    const ros1::EyeHealth& b = *eyes[eye][1];
    if (e.received == b.received) {
      silent += (silent.empty() ? "" : " and ") + topics[eye];
    } else if (e.received - e.unconvertible == b.received - b.unconvertible) {
      unusable += (unusable.empty() ? "" : "; ") + e.last_error;
    }
  }
  if (!silent.empty()) return "no frames on " + silent + " " + span;
  if (!unusable.empty()) return unusable;
  return "no pair within the " + ms_text(options.sync_tolerance_s * 1e3) + " sync tolerance " +
         span + ": the newest stamps on " + topics[0] + " and " + topics[1] + " differ by " +
         ms_text(std::abs(static_cast<double>(now.left.last_stamp_ns - now.right.last_stamp_ns)) *
                 1e-6);
}

core::Image rgb_image(ros1::EyeFrame& frame) {
  core::Image image;
  image.width = frame.width;
  image.height = frame.height;
  image.channels = 3;
  image.pixels = std::move(frame.rgb);
  return image;
}

class Ros1Source final : public vision::StereoSource {
 public:
  Ros1Source(std::unique_ptr<ros1::CameraLink> link, Ros1StereoSourceOptions options, int width,
             int height, double fps, std::uint64_t last_number)
      : link_(std::move(link)),
        options_(std::move(options)),
        width_(width),
        height_(height),
        fps_(fps),
        last_number_(last_number),
        first_number_(last_number),
        window_start_ns_(core::monotonic_ns()),
        window_health_(link_->health()) {}

  std::string name() const override { return "ros"; }
  int width() const override { return width_; }
  int height() const override { return height_; }
  double fps() const override { return fps_; }

  Result<vision::StereoCapture> capture() override {
    const ros1::CameraLinkHealth before = link_->health();
    auto pair = link_->next_pair(last_number_, ns(core::s_to_ns(options_.frame_timeout_s)));
    const std::int64_t now = core::monotonic_ns();
    if (!pair) {
      if (failing_since_ns_ == 0) failing_since_ns_ = now;
      return Error{why_no_pairs(link_->health(), before, options_,
                                "for " + seconds_text(options_.frame_timeout_s))};
    }
    if (failing_since_ns_ != 0) {
      spdlog::info("ros: pairs again after {:.1f} s", core::ns_to_s(now - failing_since_ns_));
      failing_since_ns_ = 0;
    }
    last_number_ = pair->number;
    for (const ros1::EyeFrame* eye : {&pair->left, &pair->right}) {
      if (eye->width != width_ || eye->height != height_) {
        const std::string& topic = eye == &pair->left ? options_.left_topic : options_.right_topic;
        return Error{"the images on " + topic + " are now " + std::to_string(eye->width) + "x" +
                     std::to_string(eye->height) + ", they were " + std::to_string(width_) + "x" +
                     std::to_string(height_) + " at start (restart the vision server)"};
      }
    }
    window_.add(pair->pairing_error_ns());
    total_.add(pair->pairing_error_ns());
    if (now - window_start_ns_ >= core::s_to_ns(options_.stats_period_s)) log_window(now);

    vision::StereoCapture capture;
    capture.frame_number = pair->number - first_number_;
    capture.capture_ns_left = pair->left.capture_ns;
    capture.capture_ns_right = pair->right.capture_ns;
    capture.left = rgb_image(pair->left);
    capture.right = rgb_image(pair->right);
    return capture;
  }

  void release() override {
    const ros1::CameraLinkHealth health = link_->health();
    spdlog::info("ros: {} pairs in all, {}; unpaired frames dropped: left {}, right {}",
                 total_.pairs, total_.text(), health.left.unpaired, health.right.unpaired);
  }

 private:
  void log_window(std::int64_t now) {
    const ros1::CameraLinkHealth health = link_->health();
    const double span_s = core::ns_to_s(now - window_start_ns_);
    spdlog::info(
        "ros: {} pairs in {:.1f} s ({:.1f} per s), {}; unpaired frames dropped: left {}, "
        "right {}",
        window_.pairs, span_s, static_cast<double>(window_.pairs) / span_s, window_.text(),
        health.left.unpaired - window_health_.left.unpaired,
        health.right.unpaired - window_health_.right.unpaired);
    window_ = {};
    window_start_ns_ = now;
    window_health_ = health;
  }

  std::unique_ptr<ros1::CameraLink> link_;
  Ros1StereoSourceOptions options_;
  int width_, height_;
  double fps_;
  std::uint64_t last_number_;   // the link's number of the last pair taken
  std::uint64_t first_number_;  // taken while opening: frame numbers start after it
  PairingFigures window_, total_;
  std::int64_t window_start_ns_;
  ros1::CameraLinkHealth window_health_;
  std::int64_t failing_since_ns_ = 0;
};

// The first pairs: their size is the source's, and (fps 0) their stamps give the rate.
struct FirstPairs {
  int width = 0, height = 0;
  double fps = 0.0;
  std::uint64_t last_number = 0;
};

Result<FirstPairs> first_pairs(ros1::CameraLink& link, const Ros1StereoSourceOptions& options,
                               std::int64_t deadline_ns) {
  const ros1::CameraLinkHealth before = link.health();
  auto first = link.next_pair(0, ns(deadline_ns - core::monotonic_ns()));
  if (!first) {
    return Error{why_no_pairs(link.health(), before, options,
                              "within " + seconds_text(options.startup_timeout_s) + " of start")};
  }
  if (first->left.width != first->right.width || first->left.height != first->right.height) {
    return Error{"the images on " + options.left_topic + " (" + std::to_string(first->left.width) +
                 "x" + std::to_string(first->left.height) + ") and " + options.right_topic + " (" +
                 std::to_string(first->right.width) + "x" + std::to_string(first->right.height) +
                 ") differ in size; the vision server streams one size for both eyes"};
  }
  FirstPairs out{first->left.width, first->left.height, options.fps, first->number};
  spdlog::info("ros: first pair: {} {}x{} {}, {} {}x{} {}, pairing error {}", options.left_topic,
               first->left.width, first->left.height, first->left.encoding, options.right_topic,
               first->right.width, first->right.height, first->right.encoding,
               ms_text(static_cast<double>(first->pairing_error_ns()) * 1e-6));
  if (out.fps > 0.0) return out;
  // A few more pairs, for up to a second: the rate from the median interval between
  // consecutive stamps, so that a pair lost on a loaded machine (an interval twice as long)
  // does not lower it, as a count over the time span would.
  std::vector<std::int64_t> stamps{first->left.stamp_ns};
  const std::int64_t until = core::monotonic_ns() + core::s_to_ns(1.0);
  while (out.last_number - first->number < 10) {
    auto next = link.next_pair(out.last_number, ns(until - core::monotonic_ns()));
    if (!next) break;
    out.last_number = next->number;
    stamps.push_back(next->left.stamp_ns);
  }
  std::vector<std::int64_t> intervals;
  for (std::size_t k = 1; k < stamps.size(); ++k) {
    if (stamps[k] > stamps[k - 1]) intervals.push_back(stamps[k] - stamps[k - 1]);
  }
  if (!intervals.empty()) {
    const auto middle = intervals.begin() + static_cast<std::ptrdiff_t>(intervals.size() / 2);
    std::nth_element(intervals.begin(), middle, intervals.end());
    out.fps = 1.0 / core::ns_to_s(*middle);
  }
  return out;
}

}  // namespace

bool ros1_stereo_source_built() {
  return true;
}

Result<Ros1StereoSource> open_ros1_stereo_source(const Ros1StereoSourceOptions& options) {
  if (!(options.startup_timeout_s > 0.0 && options.frame_timeout_s > 0.0 &&
        options.stats_period_s > 0.0 && options.fps >= 0.0)) {
    return Error{"the ROS source's timeouts and stats period must be positive, its fps >= 0"};
  }
  ros1::CameraLinkOptions link_options;
  link_options.master_uri = options.master_uri;
  link_options.left_topic = options.left_topic;
  link_options.right_topic = options.right_topic;
  link_options.sync_tolerance_s = options.sync_tolerance_s;
  std::string error;
  auto link = ros1::CameraLink::start(
      link_options, [](const std::string& line) { spdlog::info("ros: {}", line); }, &error);
  if (!link) return Error{error};

  const std::int64_t deadline = core::monotonic_ns() + core::s_to_ns(options.startup_timeout_s);
  auto first = first_pairs(*link, options, deadline);
  if (!first) return first.error();

  Ros1StereoSource opened;
  if (options.camera_info) {
    // camera_info comes with the images; a second more for one that was just connected.
    const std::int64_t info_deadline = std::max(deadline, core::monotonic_ns() + core::s_to_ns(1));
    while (!(link->camera_info(false) && link->camera_info(true)) &&
           core::monotonic_ns() < info_deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    const auto left = link->camera_info(false);
    const auto right = link->camera_info(true);
    if (!left || !right) {
      const std::string missing =
          !left && !right
              ? ros1::camera_info_topic(options.left_topic) + " and " +
                    ros1::camera_info_topic(options.right_topic)
              : ros1::camera_info_topic(!left ? options.left_topic : options.right_topic);
      opened.warnings.push_back("no camera_info on " + missing + " within " +
                                seconds_text(options.startup_timeout_s) +
                                " of start: GetCameraInfo serves no calibration (publish "
                                "camera_info beside the images, or give --calibration)");
    } else {
      auto calibration = ros1::calibration_from_camera_info(
          *left, *right, {options.left_topic, first->width, first->height},
          {options.right_topic, first->width, first->height});
      if (!calibration) return calibration.error();
      opened.calibration_yaml = std::move(calibration->yaml);
      for (auto& warning : calibration->warnings) opened.warnings.push_back(std::move(warning));
    }
  }
  opened.source = std::make_unique<Ros1Source>(std::move(link), options, first->width,
                                               first->height, first->fps, first->last_number);
  return opened;
}

}  // namespace telear::drivers
