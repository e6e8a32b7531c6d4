#pragma once
// Manual capture for registration (docs/registration.md, "Manual capture"): the operator jogs
// the arm (the robot client's ordinary jog or plan messages) and confirms each pose; the
// capture folder grows pose by pose in exactly the format capture_for_registration writes
// (telear/vision/capture_folder.hpp), so `telear register --captures DIR` reads either.
//
// open():              creates DIR (refusing one that already holds a capture), asks the
//                      vision server for its calibration and writes it as DIR/cameras.yaml
// add_current_pose():  waits until the arm is at rest (mode idle, no trajectory, and the
//                      measured joints still within rest_tolerance_rad after settle_s), grabs
//                      frames_per_pose stereo frames exposed after that instant whose eyes
//                      are within max_sync_skew_ns, writes them, appends the pose and rewrites
//                      DIR/capture.yaml -- the folder on disk is complete after every pose.
//                      The target is then detected in the new images (per eye: seen or not),
//                      and the coverage so far is updated.
// solve():             register_captures on the folder as it stands, the report beside it.
//
// The images must be the camera's own (the calibration's size, lossless as the stream
// allows): the vision client given here should ask for the source's size and JPEG quality 100
// (the console opens one for that, beside its reduced live view). The lease is the caller's
// to take; a pose is only ever recorded at rest, never moved to.
//
// Also here: the pieces capture_for_registration shares (folder, camera info, frames at rest).

#include <Eigen/Core>
#include <atomic>
#include <cstdint>
#include <future>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "telear/core/marker_mount.hpp"
#include "telear/core/result.hpp"
#include "telear/core/robot_model.hpp"
#include "telear/net/robot_client.hpp"
#include "telear/net/vision_client.hpp"
#include "telear/vision/capture_folder.hpp"
#include "telear/vision/capture_observations.hpp"
#include "telear/vision/capture_registration.hpp"
#include "telear/vision/registration_target.hpp"

namespace telear::session {

// [SECTION] shared with capture_for_registration

// Creates `directory` (refusing one that holds capture.yaml) and asks the vision server for
// its calibration (refusing a server without one: registration needs the intrinsics).
// Errors start with "capture: ".
Result<net::CameraInfoReply> open_capture_folder(net::VisionClient& vision,
                                                 const std::string& directory);

// Writes the calibration the poses are captured with as DIR/cameras.yaml and names it in
// `capture` (nothing when the server sent no file text).
Status write_capture_cameras(const std::string& directory, const net::CameraInfoReply& info,
                             vision::CaptureSet& capture);

// The newest frame whose two eyes were both captured after `after_ns` (client clock) and whose
// id is above `after_id`, waiting up to timeout_s; null when none came.
std::shared_ptr<const net::DecodedStereoFrame> frame_after(net::VisionClient& vision,
                                                           std::int64_t after_ns,
                                                           std::uint64_t after_id,
                                                           double timeout_s);

struct PoseFramesOptions {
  int frames = 3;
  std::int64_t max_sync_skew_ns = 5'000'000;
  double timeout_s = 60.0;
};

// Frames exposed after the rest state `rest` (its capture time on the client clock), written
// as pose `index`'s images under `directory`; `last_frame_id` is advanced so that a frame is
// never used twice. Returns the frames written (empty: no synchronized frame in time); errors:
// an image that cannot be written.
Result<std::vector<vision::CapturedFrame>> capture_pose_frames(net::VisionClient& vision,
                                                               const std::string& directory,
                                                               int index,
                                                               const net::RobotStateSample& rest,
                                                               const PoseFramesOptions& options,
                                                               std::uint64_t& last_frame_id);

// [SECTION] the manual capture

struct CaptureSessionOptions {
  std::string directory;    // created when missing; must not hold a capture.yaml
  int frames_per_pose = 3;  // 1..30
  double settle_s = 0.3;    // 0..10, at rest before the frames
  double rest_tolerance_rad = 2e-3;
  double rest_timeout_s = 30.0;  // for the arm to come to rest, and again for the frames
  std::int64_t max_sync_skew_ns = 5'000'000;
  std::optional<core::MarkerMount> marker;  // unset: the robot's own (core::marker_mount_for)
  // The target on the flange, where the mount sits (unset: the mount's marker); detected in
  // every pose and named in the folder for `telear register`.
  std::optional<vision::RegistrationTarget> target;
  vision::HandEyeOptions hand_eye;

  Status validate() const;  // names the field and the range
};

// What one added pose gave.
struct CapturedPoseReport {
  int index = 0;  // 0-based, as the folder names it (pose_007); "pose N" in messages
  int frames = 0;
  std::string target = "marker";  // or "board": what the summary says was seen
  bool left_seen = false;         // the target found in that eye (in a frame, corners steady)
  bool right_seen = false;
  Eigen::VectorXd q;               // rad, measured at rest
  std::vector<std::string> notes;  // the detection's, e.g. not found, moved between frames
  std::string summary() const;     // "pose 3: 3 frames, marker seen left and right"
};

class CaptureSession {
 public:
  // The robot and vision clients must be started and outlive the session. Errors: invalid
  // options, the folder or the camera info (open_capture_folder), no marker for the robot.
  static Result<std::unique_ptr<CaptureSession>> open(const core::RobotModel& model,
                                                      net::RobotClient& robot,
                                                      net::VisionClient& vision,
                                                      CaptureSessionOptions options);

  // Waits for rest, grabs the frames, appends the pose (blocks for about settle_s plus the
  // frames; longer while the arm still moves). Errors: no robot state, e-stop, the arm not at
  // rest within rest_timeout_s, no synchronized frame, a frame of another size than the
  // calibration, files that cannot be written -- the manifest is left as before the call.
  Result<CapturedPoseReport> add_current_pose();

  // The same without blocking the caller (the console: its view, jog and e-stop stay live
  // while the arm comes to rest): the waiting, the frames and the detection run on a worker
  // thread; poll_add(), called from the caller's thread (every display frame), appends the
  // pose when the worker is done and returns the outcome once. One at a time: a second
  // start_add_pose() (or add_current_pose()) while adding() is refused. Closing the session
  // cancels the wait for rest.
  Status start_add_pose();
  bool adding() const;
  std::optional<Result<CapturedPoseReport>> poll_add();
  // Adds finished through poll_add, and the last one's error (empty: it succeeded).
  int adds_finished() const { return adds_finished_; }
  const std::string& last_add_error() const { return last_add_error_; }

  // register_captures on the folder as it stands (needs hand_eye.min_views poses with the
  // target seen, turning about two axes). The last success is kept in solution().
  Result<vision::CaptureRegistration> solve();

  const std::string& directory() const { return options_.directory; }
  const core::MarkerMount& marker() const { return *options_.marker; }
  const vision::RegistrationTarget& target() const { return *options_.target; }
  const vision::CaptureSet& capture() const { return capture_; }
  const std::vector<CapturedPoseReport>& poses() const { return reports_; }
  const vision::StereoCameraModel& cameras() const { return info_.cameras; }
  // The target's detections so far (views named "pose N"), and their coverage image (both
  // eyes side by side at the cameras' size, BGR: vision::coverage_image).
  const vision::CaptureObservations& detected() const { return detected_; }
  cv::Mat coverage() const;
  // Counts every change (an added pose, a solution) so a viewer knows when to redraw.
  int revision() const { return revision_; }
  const std::optional<vision::CaptureRegistration>& solution() const { return solution_; }
  const std::string& last_solve_error() const { return solve_error_; }

  ~CaptureSession();
  CaptureSession(const CaptureSession&) = delete;
  CaptureSession& operator=(const CaptureSession&) = delete;

 private:
  // A pose's frames written and its target detected, not yet in the folder's manifest.
  struct PoseCapture {
    int index = 0;
    vision::CapturedPose pose;
    vision::CaptureObservations detected;
    std::uint64_t last_frame_id = 0;  // the newest frame used
  };
  // The slow half of adding a pose; reads only what open() set, so it may run on the worker.
  Result<PoseCapture> capture_pose(int index, std::uint64_t last_frame_id);
  // The quick half: appends the pose and rewrites the manifest (the caller's thread).
  Result<CapturedPoseReport> append_pose(PoseCapture captured);
  CaptureSession(const core::RobotModel& model, net::RobotClient& robot, net::VisionClient& vision,
                 CaptureSessionOptions options);
  Result<net::RobotStateSample> wait_for_rest();

  const core::RobotModel& model_;
  net::RobotClient& robot_;
  net::VisionClient& vision_;
  CaptureSessionOptions options_;
  net::CameraInfoReply info_;
  vision::CaptureSet capture_;
  std::vector<CapturedPoseReport> reports_;
  vision::CaptureObservations detected_;
  std::optional<vision::CaptureRegistration> solution_;
  std::string solve_error_;
  std::uint64_t last_frame_id_ = 0;
  int revision_ = 0;
  std::future<Result<PoseCapture>> pending_;
  std::atomic<bool> cancel_{false};
  int adds_finished_ = 0;
  std::string last_add_error_;
};

}  // namespace telear::session
