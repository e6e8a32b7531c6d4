#include "telear/session/live_series.hpp"

#include <cassert>
#include <cmath>
#include <cstdio>

namespace telear::session {

Status LiveSeriesOptions::validate() const {
  auto positive = [](const char* name, double value) -> Status {
    if (!std::isfinite(value) || value <= 0.0) {
      char text[128];
      std::snprintf(text, sizeof text, "live series: %s %g must be positive and finite", name,
                    value);
      return Error{text};
    }
    return Status::Ok();
  };
  if (Status s = positive("window_s", window_s); !s) return s;
  if (Status s = positive("rate_bucket_s", rate_bucket_s); !s) return s;
  if (rate_bucket_s > window_s) {
    char text[128];
    std::snprintf(text, sizeof text, "live series: rate_bucket_s %g must be at most window_s %g",
                  rate_bucket_s, window_s);
    return Error{text};
  }
  if (capacity < 2) {
    return Error{"live series: capacity " + std::to_string(capacity) + " must be >= 2"};
  }
  return Status::Ok();
}

namespace {
// The buckets the window spans (a partial one at each end), at most the capacity.
std::size_t video_capacity(const LiveSeriesOptions& o) {
  const double buckets = std::ceil(o.window_s / o.rate_bucket_s) + 2.0;
  return std::min(o.capacity, static_cast<std::size_t>(buckets));
}

const LiveSeriesOptions& checked(const LiveSeriesOptions& options) {
  assert(options.validate().ok() && "LiveSeries: options must validate()");
  return options;
}
}  // namespace

LiveSeries::LiveSeries(LiveSeriesOptions options)
    : options_(checked(options)),
      tracking_(options_.capacity),
      latency_(options_.capacity),
      video_(video_capacity(options_)),
      display_(options_.capacity) {}

void LiveSeries::update(double t, const net::RobotStateSample* state, double state_t,
                        const net::DecodedStereoFrame* frame, const DisplayDecision& display) {
  now_ = t;
  if (state != nullptr && state->sequence > last_sequence_) {
    last_sequence_ = state->sequence;
    add_tracking(state_t, state->state);
  }
  advance_video(t);
  // Decode times on the client's monotonic clock order the frames, across reconnections too.
  if (frame != nullptr && frame->decoded_ns > last_decoded_ns_) {
    last_decoded_ns_ = frame->decoded_ns;
    latency_.push({t, frame->latency});
    ++video_.back().frames;
    video_.back().bytes += static_cast<double>(frame->message_bytes);
  }
  display_.push({t, display.mode, display.frame_stale});
  trim(t);
}

void LiveSeries::add_tracking(double t, const core::RobotState& state) {
  const Eigen::Index n = state.q.size();
  if (n == 0 || state.q_commanded.size() != n) return;
  if (joints_ == 0) joints_ = static_cast<int>(n);
  if (n != joints_ || !state.q.allFinite() || !state.q_commanded.allFinite()) return;
  TrackingSample& sample = tracking_.push();  // reuses the slot's vector once the ring is full
  sample.t = t;
  sample.error = state.q_commanded - state.q;
}

void LiveSeries::advance_video(double t) {
  const double width = options_.rate_bucket_s;
  const auto bucket = static_cast<std::int64_t>(std::floor(t / width));
  auto start = [&](std::int64_t index) {
    video_.push({static_cast<double>(index) * width, width, 0, 0.0});
    video_bucket_ = index;
  };
  if (video_.empty() || bucket - video_bucket_ > static_cast<std::int64_t>(video_.capacity())) {
    video_.clear();  // first, or a gap longer than the window: nothing to keep
    start(bucket);
    return;
  }
  // Every second (bucket) without a frame counts, as 0 frames: the rate drops while the video
  // stops, with no update needed from a frame.
  while (video_bucket_ < bucket) start(video_bucket_ + 1);
}

void LiveSeries::trim(double t) {
  const double oldest = t - options_.window_s;
  while (!tracking_.empty() && tracking_.front().t < oldest) tracking_.pop_front();
  while (!latency_.empty() && latency_.front().t < oldest) latency_.pop_front();
  while (!display_.empty() && display_.front().t < oldest) display_.pop_front();
  // A bucket goes once it has ended before the window (the newest one always stays).
  while (video_.size() > 1 && video_.front().t + video_.front().duration_s <= oldest) {
    video_.pop_front();
  }
}

}  // namespace telear::session
