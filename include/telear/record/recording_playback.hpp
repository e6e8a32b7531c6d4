#pragma once
// A recording played back: what the operator's AR view showed at any time of an MCAP file
// that SessionRecorder wrote -- the stereo frame (decoded from its recorded JPEGs), the ghost,
// the real arm, the AR/VR mode -- and the calibration it was drawn through. `telear replay`
// draws it (console/replay_app.hpp).
//
// "At time t" (seconds from the recording's start, its log times) means what the live view had
// then: the frame the view drew (the newest /telear/latency message names the pair by its
// capture stamp; an operator's view logs it when it first draws the frame, `telear record` at
// its decode; a recording without latency messages falls back to the newest frame received),
// the newest ghost and robot state, the last AR/VR switch.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "telear/core/image.hpp"
#include "telear/core/result.hpp"
#include "telear/record/recording_series.hpp"
#include "telear/vision/camera_model.hpp"

namespace telear::record {

struct PlaybackMoment {
  double t = 0.0;
  std::uint64_t log_ns = 0;
  std::optional<std::size_t> frame;    // index into series().frames[0]; none before the first
  const JointSample* ghost = nullptr;  // null: none recorded yet
  const JointSample* robot = nullptr;  // the measured arm
  bool vr = false;                     // the recorded display mode (DISPLAY_MODE events)
  // t minus the frame's capture time (left eye): the age the live view judged it stale by.
  std::optional<double> frame_age_s;
};

struct PlaybackFrame {
  std::size_t index = 0;
  std::uint64_t log_ns = 0;
  std::int64_t stamp_ns = 0;  // capture time (left eye)
  core::Image left, right;    // RGB8, decoded from the recorded JPEGs
};

class RecordingPlayback {
 public:
  // Reads the series (recording_series.hpp), the calibration.yaml and workspace.yaml
  // attachments. Errors: the file, no calibration attachment ("... records no calibration:
  // nothing to draw the arm through"), a calibration that does not parse or is not stereo.
  static Result<RecordingPlayback> open(const std::string& path);
  RecordingPlayback(RecordingPlayback&&) noexcept;
  RecordingPlayback& operator=(RecordingPlayback&&) noexcept;
  ~RecordingPlayback();

  const RecordingSeries& series() const;
  double duration_s() const { return series().duration_s(); }
  // The recorded cameras (with T_cam_base), at their recorded size.
  const vision::StereoCameraModel& cameras() const;
  const std::string& workspace_yaml() const;  // empty: none recorded
  // telear.session metadata: which robot the operator loaded ("robot_spec", else the robot's
  // name) and the tip given with it ("robot_tip"; empty: the robot file's).
  std::string robot_spec() const;
  std::string robot_tip() const;

  // What the view had at `t` s from the start (clamped to [0, duration]).
  PlaybackMoment at(double t) const;
  // Both eyes of frame `index`, decoded (the last one is kept: repeated calls are free).
  // Errors: the index, the file, a JPEG that does not decode.
  Result<const PlaybackFrame*> frame(std::size_t index);

 private:
  std::int64_t pair_stamp(std::size_t index) const;  // the later eye's capture stamp
  struct State;
  explicit RecordingPlayback(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

}  // namespace telear::record
