#pragma once
// What the demo records while it drives a session::Session (docs/demo.md): one display tick at a
// time (session update, AR view, one video frame), the per-stage video latency of every new frame
// shown, the live marker residual of every registration check per eye, the composed stereo
// view as an MP4, and named key frames (PNG).
//
// The MP4 is H.264 (fourcc avc1, OpenCV's FFmpeg backend) so browsers play it; when this
// OpenCV cannot open an H.264 writer, MPEG-4 part 2 (mp4v), with a warning naming the codec
// used: logged (spdlog, warn) and kept in Recording::video_warning beside video_codec, which
// the demo's report.json and report.md carry. Debian 12's OpenCV (FFmpeg with libx264)
// writes avc1; tests/apps/demo_cli_test.cpp checks that it does.
// Latencies in s, residuals in px. Ticks are paced at `fps` by sleeping: call from one thread,
// the one whose OpenGL context the ArView uses.

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "telear/core/image.hpp"
#include "telear/core/result.hpp"
#include "telear/net/latency_stages.hpp"
#include "telear/render/ar_view.hpp"
#include "telear/session/session.hpp"
#include "telear/vision/videoio.hpp"

namespace telear::lab {

// Per eye (0 left, 1 right): one entry per registration check that found the marker.
struct ResidualSeries {
  std::vector<double> rms_px[2];
  std::vector<double> max_px[2];
  // rms_px split by the arm's state at the frame (session::StereoResidual::arm_moving).
  std::vector<double> rms_px_at_rest[2];
  std::vector<double> rms_px_moving[2];
  int misses[2] = {0, 0};    // checks where the marker was not found
  std::string last_miss[2];  // the last such check's message
};

struct Recording {
  net::LatencySeries latency;  // per stage (net::kLatencyStages), one entry per frame shown, s
  ResidualSeries residuals;
  int ticks = 0;
  int frames_shown = 0;
  int video_frames = 0;
  std::string video_path;               // empty: no video
  std::string video_codec;              // "avc1" (H.264) or "mp4v"; empty: no video
  std::string video_warning;            // set when H.264 could not be opened
  std::vector<std::string> key_frames;  // PNG paths, in order
  // When each key frame's view was drawn (the monotonic clock): where a replay of the task's
  // recording finds it (its ghost message is stamped with the same time).
  std::vector<std::int64_t> key_frame_view_ns;
  // Whether each key frame's view drew the predicted arm (a replay draws none).
  std::vector<bool> key_frame_predicted;
  // Whether the session held the robot's states back then (injected_state_delay_s): the view
  // drew the arm late, the recording holds the states as they arrived.
  std::vector<bool> key_frame_states_held_back;
};

struct RecorderOptions {
  std::string out_dir;
  double fps = 15.0;  // display ticks (and video frames) per second, > 0
  bool video = true;  // false: no MP4 (key frames still written)
  // Called with the session's view at every tick, after its update, and the time it is drawn
  // (telear demo --record: the ghost drawn, the shown frame's latency;
  // session::record_session_view).
  std::function<void(const session::SessionView&, std::int64_t monotonic_ns)> on_view;
};

class SessionRecorder {
 public:
  SessionRecorder(session::Session& session, render::ArView& view, RecorderOptions options);
  ~SessionRecorder();
  SessionRecorder(const SessionRecorder&) = delete;
  SessionRecorder& operator=(const SessionRecorder&) = delete;

  // Opens OUT/demo_stereo.mp4 for width x height frames (H.264, else mp4v); Ok and nothing
  // when options.video is false. An error when no writer opens at all.
  Status open_video(int width, int height);
  // One display frame: session update, AR view, video frame; paced at options.fps.
  void tick();
  void ticks(int count) {
    for (int i = 0; i < count; ++i) tick();
  }
  // Writes the last composed view to OUT/NAME.png; returns the path.
  Result<std::string> key_frame(const std::string& name);
  void close_video();

  const Recording& recording() const { return recording_; }

 private:
  session::Session& session_;
  render::ArView& view_;
  RecorderOptions options_;
  std::unique_ptr<vision::VideoWriter> writer_;  // the videoio plugin's; null: no video
  Recording recording_;
  std::optional<std::chrono::steady_clock::time_point> last_;
  std::uint64_t last_frame_id_ = 0;
  int residual_checks_ = 0;
  core::Image last_image_;
  std::int64_t last_view_ns_ = 0;       // when last_image_'s view was drawn
  bool last_view_predicted_ = false;    // ... with the predicted arm
  bool last_view_states_held_ = false;  // ... with the states held back
};

}  // namespace telear::lab
