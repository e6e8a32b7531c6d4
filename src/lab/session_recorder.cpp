#include "telear/lab/session_recorder.hpp"

#include <spdlog/spdlog.h>

#include <thread>

#include "telear/core/clock.hpp"
#include "telear/render/image_io.hpp"
#include "telear/view/ar_view_input.hpp"

namespace telear::lab {

SessionRecorder::SessionRecorder(session::Session& session, render::ArView& view,
                                 RecorderOptions options)
    : session_(session), view_(view), options_(std::move(options)) {}

SessionRecorder::~SessionRecorder() = default;

void SessionRecorder::close_video() {
  if (writer_) writer_->close();
  writer_.reset();
}

Status SessionRecorder::open_video(int width, int height) {
  if (!options_.video) return Status::Ok();
  const std::string path = options_.out_dir + "/demo_stereo.mp4";
  auto writer = vision::open_mp4_writer({path, width, height, options_.fps});
  if (!writer) return writer.error();
  writer_ = std::move(*writer);
  recording_.video_codec = writer_->codec();
  recording_.video_warning = writer_->warning();
  if (!recording_.video_warning.empty()) {
    // Logged here as well as recorded (the demo's report, the console's status), so that no
    // caller can lose it: the file plays in fewer places than the docs promise.
    spdlog::warn("session recorder: {}", recording_.video_warning);
  }
  recording_.video_path = path;
  return Status::Ok();
}

void SessionRecorder::tick() {
  using Clock = std::chrono::steady_clock;
  const double period = 1.0 / options_.fps;
  const auto now = Clock::now();
  const double dt = last_ ? std::chrono::duration<double>(now - *last_).count() : period;
  last_ = now;
  session_.update(dt);
  const session::SessionView& v = session_.view();
  last_view_ns_ = session_.state_taken_ns();  // the view's time (session_recording.hpp)
  if (options_.on_view) options_.on_view(v, last_view_ns_);
  last_view_predicted_ = v.show_prediction && view_.options().show_predicted;
  last_view_states_held_ = session_.options().injected_state_delay_s > 0.0;
  if (v.frame && v.frame->frame_id != last_frame_id_) {
    last_frame_id_ = v.frame->frame_id;
    recording_.latency.add(v.frame->latency);
    ++recording_.frames_shown;
  }
  const session::SessionStats stats = session_.stats();
  if (stats.residual_checks != residual_checks_) {
    residual_checks_ = stats.residual_checks;
    const session::EyeResidual* eyes[2] = {&stats.residual.left, &stats.residual.right};
    ResidualSeries& r = recording_.residuals;
    for (int i = 0; i < 2; ++i) {
      if (eyes[i]->valid()) {
        r.rms_px[i].push_back(eyes[i]->rms_px);
        r.max_px[i].push_back(eyes[i]->max_px);
        (stats.residual.arm_moving ? r.rms_px_moving : r.rms_px_at_rest)[i].push_back(
            eyes[i]->rms_px);
      } else {
        ++r.misses[i];
        r.last_miss[i] = eyes[i]->message;
      }
    }
  }
  view_.render(view::ar_view_input(v));
  last_image_ = view_.read_composed_rgb();
  if (writer_) {
    if (Status s = writer_->write(last_image_); s) {
      ++recording_.video_frames;
    } else {
      // Reported once, beside any codec warning (the demo's report), and the video ends:
      // the next frames would fail alike.
      const std::string& why = s.error().message;
      recording_.video_warning += (recording_.video_warning.empty() ? "" : "; ") + why;
      spdlog::warn("session recorder: {}", why);
      close_video();
    }
  }
  ++recording_.ticks;
  const double spent = std::chrono::duration<double>(Clock::now() - now).count();
  if (spent < period) std::this_thread::sleep_for(std::chrono::duration<double>(period - spent));
}

Result<std::string> SessionRecorder::key_frame(const std::string& name) {
  const std::string path = options_.out_dir + "/" + name + ".png";
  if (Status s = render::write_png(path, last_image_); !s.ok()) return s.error();
  recording_.key_frames.push_back(path);
  recording_.key_frame_view_ns.push_back(last_view_ns_);
  recording_.key_frame_predicted.push_back(last_view_predicted_);
  recording_.key_frame_states_held_back.push_back(last_view_states_held_);
  return path;
}

}  // namespace telear::lab
