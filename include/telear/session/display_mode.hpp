#pragma once
// Delay-aware display: whether the operator's view is AR (the live video as the background,
// the ghost over it) or VR (the whole scene drawn virtually from the robot's reported state),
// chosen from the age of the newest video frame. Pure logic: fed with the current time and the
// newest frame's capture time, both on the client's monotonic clock in seconds; no threads,
// no clock of its own, so tests drive it with made-up times.
//
//   age = now - capture time of the newest frame          (grows while no new frame comes)
//   stale  = age > late_threshold_s                      (never shown as live)
//   stopped = no new frame (a capture time not seen before) for stream_timeout_s, or none yet
//
// Automatic mode, with hysteresis so that a delay hovering around the threshold does not make
// the view flicker:
//   AR -> VR  at once, as soon as the frame is stale or the stream stopped (the operator must
//             never act on old video).
//   VR -> AR  only after `fresh_frames_to_return` consecutive NEW frames each arrived with an
//             age below late_threshold_s * fresh_fraction (default 5 frames under 150 ms), and
//             no sooner than `fresh_hold_s` (default 0.5 s) after the video was last late,
//             stopped or absent; any late update in between starts both again.
// Predict first (issue 23): while the arm can be predicted (`predicting`: a plan executes and
// the predictor draws the arm where it is now, arm_predictor.hpp), a late video does not
// switch to VR -- the view stays in AR, the frame marked stale, the predicted arm over it -- and
// a view in VR returns to AR at once. A stopped stream is VR all the same (the background is
// frozen). When prediction becomes impossible (the plan ends, a fault, a jog) the rule above
// applies again: VR at once if the video is late.
// The view starts in VR (no video yet); the first return to AR counts as a VR -> AR switch.
// Forced AR or VR (DisplayPreference) overrides the choice but not the measurements: a stale
// frame shown in forced AR is still reported as stale.
//
// Every switch is recorded (time, direction, reason, frame age) and counted, for the report.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "telear/core/result.hpp"

namespace telear::session {

enum class DisplayMode { kAR, kVR };
enum class DisplayPreference { kAutomatic, kAR, kVR };

struct DisplayModeOptions {
  double late_threshold_s = 0.25;  // a frame older than this is stale
  double fresh_fraction = 0.6;     // VR -> AR needs ages below threshold * this
  int fresh_frames_to_return = 5;  // ... for this many consecutive new frames
  double fresh_hold_s = 0.5;       // ... and this long after the video was last late / stopped
  double stream_timeout_s = 0.5;   // no new frame for this long: the stream stopped
  std::size_t max_recorded_switches = 1000;  // older switches are dropped (counts continue)

  // Errors name the field: thresholds positive and finite, fraction in (0, 1], frames >= 1,
  // hold >= 0.
  Status validate() const;
};

struct ModeSwitch {
  double time = 0.0;  // `now` of the update that switched
  DisplayMode from = DisplayMode::kVR, to = DisplayMode::kAR;
  std::optional<double> frame_age;  // s, when a frame existed
  std::string reason;
};

struct DisplayDecision {
  DisplayMode mode = DisplayMode::kVR;
  std::optional<double> frame_age;  // s; unset before the first frame
  bool frame_stale = true;          // the newest frame must be marked as stale (or there is none)
  bool stream_stopped = true;
  bool predicted = false;  // AR on late video because the arm is predicted ahead of it
  std::string reason;      // why this mode (for the status line)
};

class DisplayModeSelector {
 public:
  // options must validate() (asserted).
  explicit DisplayModeSelector(DisplayModeOptions options = {});

  const DisplayModeOptions& options() const { return options_; }
  DisplayPreference preference() const { return preference_; }
  void set_preference(DisplayPreference preference) { preference_ = preference; }

  // One display update at time `now` (s); `latest_capture` is the newest frame's capture
  // time, or nullopt when no frame has arrived yet. Times must not go backwards (a `now` before
  // the previous one is treated as equal to it). `predicting`: the arm is predicted now (see
  // the header comment).
  const DisplayDecision& update(double now, std::optional<double> latest_capture,
                                bool predicting = false);
  const DisplayDecision& decision() const { return decision_; }
  DisplayMode mode() const { return decision_.mode; }

  int ar_to_vr_switches() const { return ar_to_vr_; }
  int vr_to_ar_switches() const { return vr_to_ar_; }
  const std::vector<ModeSwitch>& switches() const { return switches_; }
  // Seconds of automatic AR on late video that prediction kept from VR (update to update).
  double predicted_late_s() const { return predicted_late_s_; }

 private:
  void switch_to(DisplayMode mode, double now, std::string reason);

  DisplayModeOptions options_;
  DisplayPreference preference_ = DisplayPreference::kAutomatic;
  DisplayDecision decision_;
  DisplayMode automatic_mode_ = DisplayMode::kVR;  // what automatic mode chose
  std::optional<double> last_capture_;             // newest capture time seen
  double last_new_frame_at_ = 0.0;                 // `now` when it was first seen
  double last_now_ = -1e300;
  double last_bad_at_ = -1e300;  // `now` when the video was last late, stopped or absent
  int fresh_count_ = 0;
  int ar_to_vr_ = 0, vr_to_ar_ = 0;
  double predicted_late_s_ = 0.0;
  std::vector<ModeSwitch> switches_;
};

const char* to_string(DisplayMode mode);
const char* to_string(DisplayPreference preference);

}  // namespace telear::session
