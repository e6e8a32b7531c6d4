#pragma once
// Preview: the ghost animated along the time-parameterized plan (a core Trajectory), over the
// live video, before anything is sent. A media-player clock over [0, duration]:
//
//   playing:  advance(dt) moves the preview time by dt * speed (dt: wall-clock seconds since
//             the last call; speed 1 = real time);
//   paused:   advance(dt) leaves the time where it is;
//   seek(t):  scrubbing, clamped to [0, duration].
//
// At the end the preview either stops there (paused at duration; play() starts again from 0)
// or, with loop set, wraps around to 0 and keeps playing. Each call returns the frame to draw:
// the time, q (dof() values) and the gripper opening commanded by then (unset when no waypoint
// up to that time commands one), sampled from the same Trajectory that will be executed, so the
// preview shows exactly the motion the robot will make.
//
// A plain value class, not thread-safe; it owns a copy of the Trajectory.

#include <Eigen/Core>
#include <optional>

#include "telear/core/result.hpp"
#include "telear/core/trajectory.hpp"

namespace telear::session {

struct PreviewOptions {
  bool loop = false;   // wrap to the start at the end instead of stopping
  double speed = 1.0;  // playback rate, (0, kMaxSpeed]
};

struct PreviewFrame {
  double time = 0.0;      // s from the plan's start
  double duration = 0.0;  // s
  Eigen::VectorXd q;
  std::optional<double> gripper;
  bool playing = false;
  bool at_end = false;  // time == duration (and not looping)
  int waypoint = 0;     // index of the last plan waypoint reached at `time` (expanded points
                        // of a Cartesian segment do not count)
};

class PlanPreview {
 public:
  static constexpr double kMaxSpeed = 16.0;

  // Starts paused at time 0. options.speed outside (0, kMaxSpeed] is clamped into it.
  explicit PlanPreview(core::Trajectory trajectory, PreviewOptions options = {});

  const core::Trajectory& trajectory() const { return trajectory_; }
  double duration() const { return trajectory_.duration(); }
  double time() const { return time_; }
  bool playing() const { return playing_; }
  bool loop() const { return options_.loop; }
  double speed() const { return options_.speed; }

  // Starts (or resumes) playing; at the end without loop it starts again from 0.
  void play();
  void pause() { playing_ = false; }
  void toggle() { playing_ ? pause() : play(); }
  // Scrubbing: jumps to t clamped to [0, duration] (non-finite t is ignored); the play state
  // is kept.
  void seek(double t);
  void set_loop(bool loop) { options_.loop = loop; }
  // Errors: speed not finite or outside (0, kMaxSpeed]; the speed is then unchanged.
  Status set_speed(double speed);

  // Advances by dt wall-clock seconds (ignored when paused, negative or not finite) and
  // returns the frame at the new time.
  PreviewFrame advance(double dt);
  PreviewFrame current() const;

 private:
  core::Trajectory trajectory_;
  PreviewOptions options_;
  double time_ = 0.0;
  bool playing_ = false;
};

}  // namespace telear::session
