#pragma once
// The robot's recent reported states by capture time, for what the video shows: a frame was
// captured at c, so the arm in it is the arm reported at c -- between two reports, linearly
// interpolated (joint by joint; the reports come at the state stream's 100 Hz, far denser than
// the arm's motion bends). Pure data, one thread (the session's); times in seconds on one
// clock, added in increasing order (an older or equal time is ignored).
//
// Used for the arm "as at the frame's capture" drawn over the video (issue 23: it must sit on
// the arm the video shows; the predicted arm is where it is now) and for the registration
// check's configuration when the server sends none.

#include <Eigen/Core>
#include <deque>
#include <optional>

namespace telear::session {

struct ArmAt {
  Eigen::VectorXd q;
  double gripper = 1.0;  // 0 closed .. 1 open, the nearer report's (it moves in steps)
};

class StateHistory {
 public:
  // Keeps the states captured in the last `span_s` before the newest (> 0).
  explicit StateHistory(double span_s = 2.0) : span_s_(span_s) {}

  void add(double capture_s, const Eigen::VectorXd& q, double gripper);
  bool empty() const { return states_.empty(); }
  std::size_t size() const { return states_.size(); }

  // The arm at `t`, interpolated between the reports around it; nullopt outside the reports'
  // times by more than `tolerance_s` (then the nearest report within it), or when the two
  // reports differ in size.
  std::optional<ArmAt> at(double t, double tolerance_s = 0.0) const;
  // The report nearest `t` (nullopt when empty).
  std::optional<ArmAt> nearest(double t) const;
  // Whether any report within `window_s` of `t` is more than `tolerance_rad` from `q` in a joint
  // (the arm moving around t).
  bool moving_near(double t, const Eigen::VectorXd& q, double window_s, double tolerance_rad) const;

 private:
  struct Entry {
    double t;
    Eigen::VectorXd q;
    double gripper;
  };
  double span_s_;
  std::deque<Entry> states_;
};

}  // namespace telear::session
