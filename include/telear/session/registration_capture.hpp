#pragma once
// Capture for registration, through the same servers the console uses (docs/registration.md,
// "Register your real cameras"): take the lease, move the arm through poses, wait for rest,
// grab several synchronized stereo frames per pose, and write a capture folder
// (telear/vision/capture_folder.hpp) that `telear register --captures DIR` solves.
//
// Poses:
//   - given (a list of joint vectors, e.g. from a poses file);
//   - automatic (auto:N): the target (the robot's marker, or the ArUco / AprilTag marker or
//     ChArUco board given as `target`) must be in both cameras' view at the arm's current
//     pose (the operator jogs it there first). There it is detected in both eyes and its pose
//     found by PnP (a board: on the corners seen); with the target's nominal mount (the
//     robot's marker file) and forward kinematics that gives a rough pose of each camera.
//     Candidate poses are drawn around the current one (arm joints within +-0.6 rad, wrist
//     joints within +-0.8 rad, inside the limits) and kept when the rough cameras see the
//     target's corners (a board: its whole chessboard) at least 30 px inside both images
//     with the target facing each camera within 50 deg, and no sight line from the target to
//     either camera crosses the arm's own body or a workspace object (marker_visibility.hpp:
//     poses where the arm hid the target cost a move and gave nothing); N of them are chosen
//     to spread the target's orientation (farthest-point sampling on the rotation angle
//     between target orientations), then visited in nearest-neighbour order to keep the
//     moves short. At each pose the first frame is checked: when an eye does not find the
//     target (a board: half its corners), the pose's frames are removed and the next of N
//     spare candidates is visited instead (a note says why), so that auto:N gives N views
//     `telear register` uses wherever the spares allow.
//
// Each move is a plan of two waypoints sent as the plan message (ExecutePlan): the server
// validates it (limits, start state, collisions when it is the authority); a refused move
// skips that pose with the server's reason in the notes. At rest (mode idle, within
// rest_tolerance_rad of the pose) the arm is left settle_s, the measured joint state is
// recorded, and frames captured after that instant are kept until frames_per_pose frames
// whose two eyes were exposed within max_sync_skew_ns of each other are written (PNG,
// lossless; the stream is asked for JPEG quality 100).

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "telear/core/arm_body.hpp"
#include "telear/core/marker_mount.hpp"
#include "telear/core/result.hpp"
#include "telear/core/robot_model.hpp"
#include "telear/core/workspace.hpp"
#include "telear/net/robot_client.hpp"
#include "telear/net/vision_client.hpp"
#include "telear/vision/capture_folder.hpp"
#include "telear/vision/registration_target.hpp"

namespace telear::session {

struct RegistrationCaptureOptions {
  std::string directory;               // created when missing; must not hold a capture.yaml
  std::vector<Eigen::VectorXd> poses;  // explicit poses (rad); used when auto_poses == 0
  int auto_poses = 0;                  // auto:N (1..200)
  std::uint64_t seed = 1;              // auto poses' candidates
  int frames_per_pose = 3;             // 1..30
  double velocity_scale = 0.3;         // (0, 1]
  double settle_s = 0.3;               // 0..10, after arriving
  double rest_tolerance_rad = 2e-3;
  double pose_timeout_s = 60.0;  // per pose: move, settle and frames
  std::int64_t max_sync_skew_ns = 5'000'000;
  // The lease's heartbeat asked of the server when the capture takes the lease (0: its
  // default, 250 ms). A machine that also simulates the robot and renders its cameras can
  // starve the heartbeat thread for longer than 250 ms (the lease lapsed mid-capture on the
  // shared 2-core test machine); the Session asks the embedded servers for 1 s as well.
  double lease_heartbeat_s = 1.0;
  core::MarkerMount marker;  // where the target sits on the flange (its pose)
  // The target on the flange (unset: the mount's own marker): detected for auto poses, its
  // spec written into the manifest for `telear register`.
  std::optional<vision::RegistrationTarget> target;
  // Auto poses: what may hide the target from a camera (marker_visibility.hpp). The arm's
  // body, unset: the robot's body file (core::body_description_for); the objects around the
  // robot, unset: none known.
  std::optional<core::ArmBody> body;
  std::optional<core::Workspace> workspace;
  // Moved there after the last pose (e.g. where the task starts); unset: the arm stays.
  std::optional<Eigen::VectorXd> finish_pose;

  Status validate() const;  // names the field and the range
};

struct CaptureProgress {
  int pose = 0;  // 1-based, of `count`
  int count = 0;
  bool captured = false;  // false: skipped (see message)
  std::string message;    // e.g. "pose 3/12: 3 frames" or why it was skipped
};

struct RegistrationCaptureResult {
  vision::CaptureSet capture;         // as written to DIR/capture.yaml
  vision::StereoCameraModel cameras;  // the vision server's calibration
  std::vector<std::string> notes;     // skipped poses and why
};

// The robot client must be started; the lease is taken here (and released at the end) unless
// already held. The vision client must be started. Errors: invalid options, no lease, no
// camera info, the target not seen at the start pose (auto), no pose captured, files that
// cannot be written -- each saying what to do.
Result<RegistrationCaptureResult> capture_for_registration(
    const core::RobotModel& model, net::RobotClient& robot, net::VisionClient& vision,
    const RegistrationCaptureOptions& options,
    const std::function<void(const CaptureProgress&)>& progress = {});

// A poses file (YAML): `poses: [[q1, ..., qn], ...]` in radians, n = dof. Errors name the file,
// the entry and what is wrong.
Result<std::vector<Eigen::VectorXd>> load_capture_poses_file(const std::string& path, int dof);

// The automatic poses alone (used by capture_for_registration; public for tests): around
// `q_start`, given rough camera models (with their T_cam_base), the marker mount and the target
// it carries (unset: its marker). `spares`, when given, receives up to `count` further
// candidates, the next farthest first: where the capture goes instead of a pose whose frames
// show the target too little.
std::vector<Eigen::VectorXd> choose_capture_poses(
    const core::RobotModel& model, const Eigen::VectorXd& q_start,
    const vision::StereoCameraModel& rough, const core::MarkerMount& marker, int count,
    std::uint64_t seed, const core::ArmBody* body = nullptr,
    const core::Workspace* workspace = nullptr,
    const std::optional<vision::RegistrationTarget>& target = std::nullopt,
    std::vector<Eigen::VectorXd>* spares = nullptr);

}  // namespace telear::session
