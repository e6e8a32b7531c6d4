#pragma once
// StereoSource: where the vision server's stereo pairs come from (the simulated rig, a pair of
// video files, a pair of V4L2 cameras, synthetic frames for benchmarks), behind one interface.
//
// Threads. A source is driven by ONE thread, the pipeline's capture thread
// (telear/net/vision_pipeline.hpp): prepare() is called once on that thread before the first
// capture() (the simulated rig creates its GL context there: a GL context is current on one
// thread only), then capture() repeatedly. capture() blocks until the next pair is due (each
// source paces itself at its nominal rate, see FramePacer) and returns it.
//
// Buffers. Each eye is a core::Image, RGB8, width x height x 3, top row first. Both eyes have
// the source's native size. Each eye carries its own capture time (telear/core/clock.hpp,
// monotonic_ns: when the source had the eye's pixels), so the pipeline's latency starts at
// the camera, not at the hand-over.

#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <thread>

#include "telear/core/clock.hpp"
#include "telear/core/image.hpp"
#include "telear/core/result.hpp"

namespace telear::vision {

// The robot configuration a simulated frame shows (rad or m per joint) and the gripper opening
// (0 closed .. 1 open), with the time of the robot state it came from (monotonic_ns of this
// machine; 0 when unknown).
struct SceneState {
  Eigen::VectorXd q;
  double gripper = 0.0;
  std::int64_t state_ns = 0;
};

struct StereoCapture {
  std::uint64_t frame_number = 0;  // 1, 2, 3 ... per captured pair of this source
  core::Image left, right;         // RGB8, native size
  std::int64_t capture_ns_left = 0, capture_ns_right = 0;
  std::optional<SceneState> scene;  // the simulated rig only

  // When the pair was complete: the later eye.
  std::int64_t pair_capture_ns() const { return std::max(capture_ns_left, capture_ns_right); }
};

class StereoSource {
 public:
  virtual ~StereoSource() = default;

  virtual std::string name() const = 0;  // "sim", "files", "v4l2", "synthetic"
  virtual int width() const = 0;         // native size of each eye
  virtual int height() const = 0;
  virtual double fps() const = 0;  // nominal rate capture() is paced at

  // Called once on the capture thread before the first capture().
  virtual Status prepare() { return {}; }
  // Called once on the capture thread after the last capture() (releases what prepare()
  // made: GL objects must be deleted on the thread whose context is current).
  virtual void release() {}
  // The next pair, when it is due. An error is a failed capture (camera unplugged, file
  // unreadable); the caller may retry.
  virtual Result<StereoCapture> capture() = 0;
};

// Paces a loop at a fixed rate without drift: the k-th frame is due at start + k / fps. A
// loop that fell behind by more than a frame restarts the schedule instead of bursting to
// catch up (a late camera frame is not followed by a burst of stale ones).
class FramePacer {
 public:
  explicit FramePacer(double fps)
      : period_ns_(fps > 0 ? static_cast<std::int64_t>(1e9 / fps) : 0) {}

  // Sleeps until the next frame is due.
  void wait() {
    if (period_ns_ <= 0) return;
    const std::int64_t now = core::monotonic_ns();
    if (next_ns_ == 0 || now - next_ns_ > period_ns_) next_ns_ = now;
    if (next_ns_ > now) std::this_thread::sleep_for(std::chrono::nanoseconds(next_ns_ - now));
    next_ns_ += period_ns_;
  }

 private:
  std::int64_t period_ns_;
  std::int64_t next_ns_ = 0;
};

}  // namespace telear::vision
