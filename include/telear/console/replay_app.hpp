#pragma once
// `telear replay F.mcap`: the console's AR view on a recording (record/recording_playback.hpp).
// The recorded stereo frames, the ghost and the real arm as recorded, drawn through the
// recorded calibration with the console's own view and defaults (so a frame drawn live and
// replayed is the same image), with play, pause, seek, step and speed in a Replay panel.
//
// Headless (--headless) it draws into an off-screen frame buffer: `--screenshot OUT.png
// --at SECONDS` writes the window as it stands at that time (scripts, tests, reports).

#include <memory>
#include <ostream>
#include <string>

#include "telear/core/image.hpp"
#include "telear/core/result.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/geometry/robot_geometry.hpp"
#include "telear/record/recording_playback.hpp"

namespace telear::console {

struct ReplayOptions {
  std::string path;  // the .mcap file
  // The arm to draw: empty name_or_path: the recording's (its telear.session metadata's
  // robot_spec, else the robot's name). Its joints must be the recording's.
  core::RobotSpec arm{"", {}, {}};
  geometry::GeometryOptions geometry;
  bool headless = false;
  int width = 1600, height = 1000;
  double at = 0.0;         // start here, s from the recording's start
  double speed = 1.0;      // 1/16 .. 16
  bool play = true;        // windowed: start playing (headless: always paused unless frames > 1)
  int frames = 0;          // headless: draw this many frames (0: one); windowed: 0 = until closed
  std::string screenshot;  // written after the last frame
};

class ReplayApp {
 public:
  // Errors: the recording (playback's), the robot (not found, other joints than recorded),
  // no GL context or window, options out of range.
  static Result<std::unique_ptr<ReplayApp>> create(const ReplayOptions& options, std::ostream& log);
  ~ReplayApp();
  ReplayApp(const ReplayApp&) = delete;
  ReplayApp& operator=(const ReplayApp&) = delete;

  bool frame();  // one display frame; false when done (window closed, frames drawn)
  int run();     // frame() until false, then the screenshot; 0, or 1 when it failed

  // [SECTION] playback control (what the panel's buttons do)
  void play() { playing_ = true; }
  void pause() { playing_ = false; }
  bool playing() const { return playing_; }
  void seek(double t);
  Status set_speed(double speed);  // 1/16 .. 16
  double time() const { return t_; }
  double duration() const;
  // Moves to the next (+1) or previous (-1) recorded frame, paused.
  void step(int frames);

  const record::RecordingPlayback& playback() const;
  // The AR view drawn at the current time (both eyes composed, as the console composes them):
  // rendered now, without the panels.
  Result<core::Image> render_view();
  const core::Image& last_image() const { return last_image_; }  // the last window image
  const record::PlaybackMoment& moment() const { return moment_; }

 private:
  struct Impl;
  explicit ReplayApp(std::unique_ptr<Impl> impl);
  Status draw_view();  // the view at t_ into the ArView's targets

  std::unique_ptr<Impl> impl_;
  double t_ = 0.0;
  double speed_ = 1.0;
  bool playing_ = false;
  int frames_ = 0;
  record::PlaybackMoment moment_;
  core::Image last_image_;
};

}  // namespace telear::console
