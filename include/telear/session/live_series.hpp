#pragma once
// The live plots' data (issue 22): what the operator watches over the last window_s seconds,
// kept by the session so that the console draws it and keeps nothing of its own (the Dear
// ImGui rule, docs/console.md "Plots"). Session::update() feeds it once per displayed frame:
//
//   series     one element per                          holds                       time t
//   tracking   new robot state (by its sequence)        q_commanded - q per joint   its capture
//   latency    new decoded frame (by its decode time)   its StageLatency (s)        taken
//   video      rate_bucket_s of the session clock       frames and message bytes    bucket start
//   display    displayed frame (update)                 AR / VR, stale              the update
//
// Times are seconds on the session clock (Session::now()). The tracking error is the servo's
// command minus the measured joint (rad, or m for a prismatic joint): the error of the robot's
// own position loop, 0 on the ideal simulated servo unless a fault is injected; the figure
// `telear report` plots from a recording (/robot/joint_commands minus /robot/joint_states,
// telear/report/recording_statistics.hpp). The execution monitor's error against the plan is
// another figure (ExecutionMonitor, the Plan panel). A frame's latency and its bytes count
// when the session takes it from the vision client, as SessionStats' windowed figures do.
//
// Bounds. Every update drops the elements older than window_s before it; each series is a
// RingBuffer of `capacity` elements (allocated once) besides, the oldest dropped first when full:
// a console drawing faster than capacity / window_s frames per second keeps a shorter display
// history, never more memory. The video's buckets cover the window: the newest one is the
// current bucket, still filling; the others are complete (empty seconds count 0 frames).
//
// A plain value class, driven from the session's thread.

#include <Eigen/Core>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/core/ring_buffer.hpp"
#include "telear/net/latency_stages.hpp"
#include "telear/net/robot_client.hpp"
#include "telear/net/vision_client.hpp"
#include "telear/session/display_mode.hpp"

namespace telear::session {

struct LiveSeriesOptions {
  double window_s = 20.0;       // how far back every series reaches
  std::size_t capacity = 4096;  // elements per series at most (the oldest go first)
  double rate_bucket_s = 1.0;   // the video's fps and bandwidth buckets

  // Errors name the field: window_s and rate_bucket_s positive and finite, rate_bucket_s at
  // most window_s, capacity >= 2.
  Status validate() const;
};

struct TrackingSample {
  double t = 0.0;         // the state's capture time, session clock (s)
  Eigen::VectorXd error;  // q_commanded - q per joint, rad or m
};

struct FrameLatencySample {
  double t = 0.0;  // when the session took the frame (s)
  net::StageLatency latency;
};

struct VideoRateBucket {
  double t = 0.0;           // the bucket covers [t, t + duration_s) (s)
  double duration_s = 1.0;  // LiveSeriesOptions::rate_bucket_s
  int frames = 0;           // decoded frames the session took in it
  double bytes = 0.0;       // their StereoFrame messages (DecodedStereoFrame::message_bytes)
  double fps() const { return frames / duration_s; }
  double bytes_per_s() const { return bytes / duration_s; }
};

struct DisplaySample {
  double t = 0.0;  // the update (s)
  DisplayMode mode = DisplayMode::kVR;
  bool stale = true;  // the newest frame was stale, or there was none
};

class LiveSeries {
 public:
  // options must validate() (asserted).
  explicit LiveSeries(LiveSeriesOptions options = {});

  const LiveSeriesOptions& options() const { return options_; }

  // One displayed frame at `t` (session clock, s): `state` the newest robot state (null: none)
  // captured at `state_t`, `frame` the newest decoded frame (null: none), `display` this
  // frame's display decision. A state or frame seen before is not counted again; a state whose
  // q and q_commanded differ in size from the first one's, or are not finite, adds no sample.
  void update(double t, const net::RobotStateSample* state, double state_t,
              const net::DecodedStereoFrame* frame, const DisplayDecision& display);

  double now() const { return now_; }     // the last update's t
  int joints() const { return joints_; }  // the tracking error's size (0 before a sample)
  const core::RingBuffer<TrackingSample>& tracking() const { return tracking_; }
  const core::RingBuffer<FrameLatencySample>& latency() const { return latency_; }
  const core::RingBuffer<VideoRateBucket>& video() const { return video_; }
  const core::RingBuffer<DisplaySample>& display() const { return display_; }

 private:
  void add_tracking(double t, const core::RobotState& state);
  void advance_video(double t);
  void trim(double t);

  LiveSeriesOptions options_;
  double now_ = 0.0;
  int joints_ = 0;
  std::uint64_t last_sequence_ = 0;
  std::int64_t last_decoded_ns_ = 0;
  std::int64_t video_bucket_ = 0;  // the newest bucket's index: its t / rate_bucket_s
  core::RingBuffer<TrackingSample> tracking_;
  core::RingBuffer<FrameLatencySample> latency_;
  core::RingBuffer<VideoRateBucket> video_;
  core::RingBuffer<DisplaySample> display_;
};

// A series as a plot draws it: `bins` equal bins of time over [t_end - span_s, t_end], oldest
// first (ImGui::PlotLines' values). Each bin holds value(sample) of largest magnitude among its
// samples, so a spike is never averaged away by the plot's resolution; an empty bin repeats the
// bin before it (0 before the first sample), so a console drawing slower than the bins does
// not draw a comb. Samples outside the span are left out. bins >= 1, span_s > 0 (asserted).
template <typename Sample, typename Value>
std::vector<float> bin_by_time(const core::RingBuffer<Sample>& samples, double t_end, double span_s,
                               int bins, Value value) {
  assert(bins >= 1 && span_s > 0.0);
  std::vector<float> out(static_cast<std::size_t>(bins), 0.0f);
  std::vector<bool> filled(out.size(), false);
  const double t0 = t_end - span_s;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const Sample& s = samples[i];
    if (s.t < t0 || s.t > t_end) continue;
    const auto bin =
        std::min<std::size_t>(out.size() - 1, static_cast<std::size_t>((s.t - t0) / span_s * bins));
    const auto v = static_cast<float>(value(s));
    if (!filled[bin] || std::abs(v) > std::abs(out[bin])) out[bin] = v;
    filled[bin] = true;
  }
  for (std::size_t b = 1; b < out.size(); ++b) {
    if (!filled[b]) out[b] = out[b - 1];
  }
  return out;
}

}  // namespace telear::session
