#include "telear/session/display_mode.hpp"

#include <cassert>
#include <cmath>
#include <cstdio>
#include <utility>

#include "telear/core/number_format.hpp"

namespace telear::session {
namespace {

std::string milliseconds(double seconds) {
  return core::format_fixed(seconds * 1000.0, 0, "ms");
}

}  // namespace

const char* to_string(DisplayMode mode) {
  return mode == DisplayMode::kAR ? "AR" : "VR";
}

const char* to_string(DisplayPreference preference) {
  switch (preference) {
    case DisplayPreference::kAutomatic:
      return "automatic";
    case DisplayPreference::kAR:
      return "AR";
    case DisplayPreference::kVR:
      return "VR";
  }
  return "?";
}

Status DisplayModeOptions::validate() const {
  auto positive = [](const char* name, double value) -> Status {
    if (!std::isfinite(value) || value <= 0.0) {
      char text[128];
      std::snprintf(text, sizeof text, "display mode: %s %g must be positive and finite", name,
                    value);
      return Error{text};
    }
    return Status::Ok();
  };
  if (Status s = positive("late_threshold_s", late_threshold_s); !s) return s;
  if (Status s = positive("stream_timeout_s", stream_timeout_s); !s) return s;
  if (!(fresh_fraction > 0.0 && fresh_fraction <= 1.0)) {
    return Error{"display mode: fresh_fraction must be in (0, 1]"};
  }
  if (fresh_frames_to_return < 1) return Error{"display mode: fresh_frames_to_return must be >= 1"};
  if (!(std::isfinite(fresh_hold_s) && fresh_hold_s >= 0.0)) {
    return Error{"display mode: fresh_hold_s must be finite and >= 0"};
  }
  return Status::Ok();
}

DisplayModeSelector::DisplayModeSelector(DisplayModeOptions options) : options_(options) {
  assert(options_.validate().ok() && "DisplayModeSelector: invalid options");
  decision_.reason = "no video yet";
}

void DisplayModeSelector::switch_to(DisplayMode mode, double now, std::string reason) {
  if (mode == decision_.mode) return;
  ModeSwitch record;
  record.time = now;
  record.from = decision_.mode;
  record.to = mode;
  record.frame_age = decision_.frame_age;
  record.reason = std::move(reason);
  (mode == DisplayMode::kVR ? ar_to_vr_ : vr_to_ar_) += 1;
  if (switches_.size() >= options_.max_recorded_switches && !switches_.empty()) {
    switches_.erase(switches_.begin());
  }
  if (options_.max_recorded_switches > 0) switches_.push_back(std::move(record));
  decision_.mode = mode;
}

const DisplayDecision& DisplayModeSelector::update(double now, std::optional<double> capture,
                                                   bool predicting) {
  if (now < last_now_) now = last_now_;
  const double since_last = last_now_ > -1e299 ? now - last_now_ : 0.0;
  last_now_ = now;
  const double threshold = options_.late_threshold_s;

  bool new_frame = false;
  if (capture && (!last_capture_ || *capture != *last_capture_)) {
    new_frame = true;
    last_capture_ = capture;
    last_new_frame_at_ = now;
  }
  DisplayDecision& d = decision_;
  if (!last_capture_) {
    d.frame_age.reset();
    d.frame_stale = true;
    d.stream_stopped = true;
  } else {
    d.frame_age = now - *last_capture_;
    d.frame_stale = *d.frame_age > threshold;
    d.stream_stopped = now - last_new_frame_at_ > options_.stream_timeout_s;
  }

  // The automatic choice, with the hysteresis of the header comment.
  std::string why;
  if (!last_capture_) {
    why = "no video yet";
  } else if (d.stream_stopped) {
    why = "video stopped: no new frame for " + milliseconds(now - last_new_frame_at_);
  } else if (d.frame_stale) {
    why =
        "video late: frame age " + milliseconds(*d.frame_age) + " over " + milliseconds(threshold);
  }
  // Predict first: late but arriving video stays (or becomes) AR while the arm is predicted.
  d.predicted = false;
  if (!why.empty() && predicting && last_capture_ && !d.stream_stopped) {
    fresh_count_ = 0;
    last_bad_at_ = now;
    if (automatic_mode_ == DisplayMode::kAR) predicted_late_s_ += since_last;
    automatic_mode_ = DisplayMode::kAR;
    d.predicted = true;
    why += "; the arm predicted ahead of it";
  } else if (!why.empty()) {
    fresh_count_ = 0;
    last_bad_at_ = now;
    automatic_mode_ = DisplayMode::kVR;
  } else if (automatic_mode_ == DisplayMode::kVR) {
    if (new_frame) {
      if (*d.frame_age < threshold * options_.fresh_fraction) {
        ++fresh_count_;
      } else {
        fresh_count_ = 0;
      }
    }
    if (fresh_count_ >= options_.fresh_frames_to_return &&
        now - last_bad_at_ >= options_.fresh_hold_s) {
      automatic_mode_ = DisplayMode::kAR;
      fresh_count_ = 0;
      why = "video fresh again: " + std::to_string(options_.fresh_frames_to_return) +
            " frames under " + milliseconds(threshold * options_.fresh_fraction);
    } else {
      why = "waiting for fresh video (" + std::to_string(fresh_count_) + " of " +
            std::to_string(options_.fresh_frames_to_return) + " frames under " +
            milliseconds(threshold * options_.fresh_fraction) + ")";
    }
  } else {
    why = "live video, frame age " + milliseconds(*d.frame_age);
  }

  DisplayMode shown = automatic_mode_;
  if (preference_ != DisplayPreference::kAutomatic) d.predicted = false;
  if (preference_ == DisplayPreference::kAR) {
    shown = DisplayMode::kAR;
    why = "AR forced by the operator" + std::string(d.frame_stale ? " (video stale)" : "");
  } else if (preference_ == DisplayPreference::kVR) {
    shown = DisplayMode::kVR;
    why = "VR forced by the operator";
  }
  switch_to(shown, now, why);
  d.reason = std::move(why);
  return d;
}

}  // namespace telear::session
