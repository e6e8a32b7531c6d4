#include "telear/session/plan_preview.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

namespace telear::session {

PlanPreview::PlanPreview(core::Trajectory trajectory, PreviewOptions options)
    : trajectory_(std::move(trajectory)), options_(options) {
  if (!std::isfinite(options_.speed) || options_.speed <= 0.0) options_.speed = 1.0;
  options_.speed = std::min(options_.speed, kMaxSpeed);
}

void PlanPreview::play() {
  if (!options_.loop && time_ >= duration()) time_ = 0.0;
  playing_ = true;
}

void PlanPreview::seek(double t) {
  if (!std::isfinite(t)) return;
  time_ = std::clamp(t, 0.0, duration());
}

Status PlanPreview::set_speed(double speed) {
  if (!std::isfinite(speed) || speed <= 0.0 || speed > kMaxSpeed) {
    char text[96];
    std::snprintf(text, sizeof text, "preview speed %g is outside (0, %g]", speed, kMaxSpeed);
    return Error{text};
  }
  options_.speed = speed;
  return Status::Ok();
}

PreviewFrame PlanPreview::advance(double dt) {
  if (playing_ && std::isfinite(dt) && dt > 0.0) {
    const double d = duration();
    const double t = time_ + dt * options_.speed;
    if (t < d) {
      time_ = t;
    } else if (options_.loop && d > 0.0) {
      time_ = std::fmod(t, d);
    } else {
      time_ = d;
      playing_ = false;
    }
  }
  return current();
}

PreviewFrame PlanPreview::current() const {
  PreviewFrame frame;
  frame.time = time_;
  frame.duration = duration();
  trajectory_.sample(time_, frame.q);
  frame.gripper = trajectory_.gripper_at(time_);
  frame.playing = playing_;
  frame.at_end = !options_.loop && time_ >= frame.duration;
  const std::vector<double>& times = trajectory_.waypoint_times();
  frame.waypoint =
      static_cast<int>(std::upper_bound(times.begin(), times.end(), time_) - times.begin()) - 1;
  frame.waypoint = std::max(frame.waypoint, 0);
  // Counted in the operator's waypoints: a Cartesian segment's expanded points are not theirs.
  const std::vector<core::JointWaypoint>& waypoints = trajectory_.waypoints();
  int expanded = 0;
  for (int k = 0; k <= frame.waypoint; ++k) {
    if (waypoints[static_cast<std::size_t>(k)].expanded) ++expanded;
  }
  frame.waypoint -= expanded;
  return frame;
}

}  // namespace telear::session
