#pragma once
// The operator's session: one robot server, one vision server, the ghost, the plan — the
// seed's workflow (rehearse on the graphical arm over the live video, then send only the
// finalized trajectory) as a library with no UI code. The console draws a Session; `telear
// demo` drives one from a script.
//
// Two arms. The *real* robot's state comes from the robot server's state stream (RobotClient,
// latest-wins); the *ghost* is local (GhostArm) and moves only by the operator's commands.
// The conventional mode — jogging the real robot directly — goes through jog_real().
//
// Plan -> preview -> validate -> execute -> monitor.
//   plan()              waypoints recorded from ghost poses (add_ghost_waypoint)
//   start_preview()     the ghost animates along the time-parameterized plan (play, pause,
//                       scrub through preview()); update() advances it
//   validate_plan()     limits, speeds, sampling, the plan's start vs the real robot now and,
//                       with a collision checker, contacts and clearance along the plan
//   execute_plan()      validates again and sends the plan itself (ExecutePlan: waypoints,
//                       timing options and the plan_hash of the trajectory the preview showed,
//                       docs/trajectory.md); the server times it with the same function and
//                       runs it only when its hash is ours. An ExecutionMonitor then compares
//                       every new robot state with that trajectory at the robot's own
//                       trajectory time and cancels the robot beyond the tolerance, saying
//                       where and how much
//
// Preview = execution. start_preview() and execute_plan() both take Plan::trajectory() and
// record its plan_hash: previewed_hash() and executed_hash() (the server's answer) are equal
// exactly when the robot runs what the operator last previewed.
//
// Delay-aware display. update() measures the age of the newest decoded frame (now - capture
// time, on this machine's clock after the clock-offset estimate) and of the robot state, and
// feeds the DisplayModeSelector: AR while the video is fresh, VR when it is late or stopped,
// back to AR with hysteresis. options.injected_video_delay_s holds each decoded frame back
// that long before the session shows it (a stand-in for a slow network, to demonstrate the
// switch); view().frame is then the newest frame old enough to be "delivered".
// options.injected_state_delay_s does the same to the robot's states (the whole link late, as
// over a WAN). While a plan executes, view().prediction is the arm predicted *now* across the
// state's age (ArmPredictor, arm_predictor.hpp: the plan plus the Smith feedback), or why not;
// while it is available a late video stays in AR with the predicted arm over it ("predict
// first", display_mode.hpp), and only when it is not does late video switch to VR.
//
// Registration check. Every options.registration_check_period_s, the newest frame's gripper
// marker is detected in both eyes and compared with where FK + calibration put it (at the
// configuration the frame shows: the frame's scene_q when the server sends it, otherwise the
// robot state nearest the frame's capture time).
//
// Threads. A Session is driven from one thread (the UI or demo loop): every member function
// must be called from it. The network threads live inside the clients, which are thread-safe.

#include <Eigen/Core>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "telear/core/motion_command.hpp"
#include "telear/core/result.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/core/robot_model.hpp"
#include "telear/core/workspace.hpp"
#include "telear/geometry/collision_checker.hpp"
#include "telear/net/latency_stages.hpp"
#include "telear/net/latency_summary.hpp"
#include "telear/net/robot_client.hpp"
#include "telear/net/vision_client.hpp"
#include "telear/session/arm_predictor.hpp"
#include "telear/session/display_mode.hpp"
#include "telear/session/execution_monitor.hpp"
#include "telear/session/ghost_arm.hpp"
#include "telear/session/ghost_clearance.hpp"
#include "telear/session/live_series.hpp"
#include "telear/session/plan.hpp"
#include "telear/session/plan_preview.hpp"
#include "telear/session/plan_validation.hpp"
#include "telear/session/registration_check.hpp"
#include "telear/session/state_history.hpp"
#include "telear/vision/frame_code.hpp"

namespace telear::session {

class CaptureSession;  // telear/session/capture_session.hpp
struct CaptureSessionOptions;

struct SessionEvent;

struct SessionOptions {
  net::RobotClientOptions robot;
  net::VisionClientOptions vision;
  // The registered stereo calibration (cameras with T_cam_base in the robot's base frame):
  // the ghost is drawn through it and the registration check uses it. Unset: none (no check).
  std::optional<vision::StereoCameraModel> cameras;
  std::optional<GripperMarker> marker;  // the gripper's marker for the registration check
  double registration_check_period_s = 0.5;
  DisplayModeOptions display;
  MonitorOptions monitor;
  double sample_rate_hz = 100.0;  // the plan's sampling for ExecuteTrajectory
  double injected_video_delay_s = 0.0;
  // Holds each robot state back this long before the session uses it (the view, the monitor,
  // the prediction, ghost = real), as injected_video_delay_s holds the video: with both the
  // whole link is late (telear demo's delay window, telear bench prediction).
  double injected_state_delay_s = 0.0;
  // The predicted arm (arm_predictor.hpp), drawn (SessionView::show_prediction) once the state
  // is prediction_min_delay_s old (below, the reported arm is where the arm is, to the eye),
  // and whenever it keeps a late video in AR (display_mode.hpp, "predict first").
  ArmPredictorOptions prediction;
  double prediction_min_delay_s = 0.1;
  double jog_validity_s = 0.5;  // a real jog's expiry from now
  // The lease's heartbeat period asked of the server (0: its default, 250 ms). A machine that
  // also simulates the robot and renders its cameras may starve the heartbeat thread for
  // longer than that; the embedded default asks for 1 s (the dead-man then acts within
  // 1.2 s of a lost operator).
  double lease_heartbeat_s = 0.0;
  std::size_t max_events = 200;
  // Called with each event as it is logged, and the monotonic clock then (a recorder writes
  // them to its /events topic: telear demo --record).
  std::function<void(const SessionEvent&, std::int64_t monotonic_ns)> on_event;
  // Collision checking (docs/collision.md). With the robot's description and the operator's
  // workspace (mesh objects loaded: geometry::load_workspace) the session builds a checker:
  // validate_plan() checks the plan continuously (contacts are errors, a clearance under
  // safety_margin_m a warning) and ghost_clearance() follows the ghost. The workspace's
  // graspable objects are not obstacles: the gripper closes on them on purpose.
  std::optional<core::RobotDescription> description;
  std::optional<core::Workspace> workspace;
  double safety_margin_m = 0.03;
  geometry::TrajectoryCheckOptions plan_check;  // how finely validate_plan() checks
  // The robot's mesh links as the convex hulls of their parts (conservative: distances at most
  // 1.4 mm smaller on the shipped arms, a 10 s plan ~25x faster), or kExact: their triangles.
  geometry::MeshCollision mesh_collision = geometry::MeshCollision::kConvexParts;
};

// The workflow step an event marks, for a recording's structured events (a recorder writes
// them as telear.record.v1.PlanEvent, whose kinds these follow one for one); kNone: a message
// only (connection, ghost rejections, registration).
enum class WorkflowStep {
  kNone,
  kLeaseAcquired,
  kLeaseReleased,
  kPreview,      // started, stopped (message says which)
  kValidate,     // message: "ok" or the report's summary
  kExecute,      // sent, refused, finished, cancelled
  kCollision,    // the plan's first contact (validation)
  kDisplayMode,  // message starts with the new mode, "ar" or "vr"
  kEStop,
  kEStopReset,
  kFault,  // the execution monitor's cancel
};

struct SessionEvent {
  double time = 0.0;  // session clock, s
  enum class Kind { kInfo, kWarning, kError } kind = Kind::kInfo;
  std::string message;
  WorkflowStep step = WorkflowStep::kNone;
  std::string plan_id;    // the plan or trajectory concerned (execute), else empty
  std::string plan_hash;  // its plan_hash (preview, validate, execute), else empty
};

// What the UI draws this frame.
struct SessionView {
  std::shared_ptr<const net::DecodedStereoFrame> frame;  // null: no frame (yet)
  DisplayDecision display;
  Eigen::VectorXd ghost_q;     // the ghost (during a preview: the preview's pose; during
  double ghost_gripper = 1.0;  // execution: the plan at the robot's trajectory time)
  std::optional<net::RobotStateSample> real;
  double real_state_age_s = 0.0;
  bool previewing = false;
  bool executing = false;
  // Chain frames of the ghost's links in contact at ghost_q (drawn red); empty without a
  // collision checker.
  std::vector<int> ghost_contact_frames;
  // The arm predicted now from the executing plan and the reported state (arm_predictor.hpp),
  // or why not; show_prediction: available and at least options.prediction_min_delay_s ahead
  // or keeping a late video in AR (display.predicted), the view draws prediction.q as a third
  // arm.
  ArmPrediction prediction;
  bool show_prediction = false;
  // The arm as reported at the shown frame's capture time (StateHistory): where the video
  // shows it (for the simulated rig, at the time of the state it drew: scene_state_ns).
  // nullopt without a frame, or without reports within 50 ms of its capture.
  std::optional<ArmAt> capture_arm;
};

using net::LatencySummary;

struct SessionStats {
  double video_fps = 0.0;  // decoded frames per second over the last ~2 s
  // The video's latency per stage over the last ~2 s, in net::kLatencyStages' order
  // (telear/net/latency_stages.hpp): latency[i] is kLatencyStages[i].
  net::StageSummaries latency{};
  double robot_state_age_s = 0.0;
  double robot_round_trip_s = 0.0;  // last ping
  double video_bytes_per_s = 0.0;
  std::uint64_t command_bytes_sent = 0;
  StereoResidual residual;  // last registration check
  int residual_checks = 0;
  double frame_age_s = 0.0;
  // Capture -> shown (glass to glass, docs/latency.md) over the last ~2 s: the frames the UI
  // drew and read back by their frame code (Session::note_shown); samples 0: not measured.
  LatencySummary shown{};
  int shown_without_code = 0;  // frames drawn in that window with no readable code of theirs
};

class Session {
 public:
  static Result<std::unique_ptr<Session>> create(core::RobotModelPtr model, SessionOptions options);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  const core::RobotModel& model() const { return *model_; }
  const SessionOptions& options() const { return options_; }

  // [SECTION] connection
  void connect();     // starts both clients (lazy connection, reconnects by itself)
  void disconnect();  // closes a registration capture, releases the lease, stops the clients
  bool connected() const { return connected_; }
  bool robot_connected() const;
  bool vision_connected() const;
  net::RobotClient& robot() { return *robot_; }
  net::VisionClient& vision() { return *vision_; }
  Status take_control();     // acquire the lease
  Status release_control();  // release it
  bool in_control() const;
  Status estop(const std::string& reason = "e-stop from the operator");
  Status reset_estop();

  // [SECTION] ghost
  GhostArm& ghost() { return ghost_; }
  const GhostArm& ghost() const { return ghost_; }
  core::MotionOutcome move_ghost(
      const core::MotionCommand& command);  // rejections become events too
  Status ghost_to_real();                   // "ghost = real"

  // The ghost's clearance where it is drawn (view().ghost_q: the preview's pose during a
  // preview), re-checked when it moves; level kUnchecked without a collision checker.
  const ClearanceState& ghost_clearance() const;
  bool checks_collisions() const { return checker_ != nullptr; }

  // [SECTION] real robot (the conventional mode)
  Result<net::JogAck> jog_real(const core::MotionCommand& command);
  Status set_real_gripper(double opening);
  // Moves the real robot to q along a validated 2-waypoint trajectory (the seed's
  // "initialize real robot").
  Result<net::TrajectoryAck> initialize_real(const Eigen::VectorXd& q);

  // [SECTION] plan
  Plan& plan() { return plan_; }
  const Plan& plan() const { return plan_; }
  Status add_ghost_waypoint(double min_duration = 0.0, std::string label = {});
  Status start_preview(PreviewOptions options = {});
  void stop_preview();
  PlanPreview* preview() { return preview_ ? &*preview_ : nullptr; }
  // Validates and logs the result (a kValidate event, and a kCollision one for the first
  // contact); check_plan() only validates.
  ValidationReport validate_plan();
  ValidationReport check_plan() const;
  // The plan_hash of the plan as it stands (its Plan::trajectory()), what execute_plan sends.
  Result<std::string> plan_hash() const;
  Result<net::PlanAck> execute_plan();
  // The hash of the trajectory the last preview showed, and the server's hash of the last
  // executed plan (empty until then).
  const std::string& previewed_hash() const { return previewed_hash_; }
  const std::string& executed_hash() const { return executed_hash_; }
  Status cancel_execution(const std::string& reason = "cancelled by the operator");
  const ExecutionMonitor* monitor() const { return monitor_ ? &*monitor_ : nullptr; }
  bool executing() const { return executing_; }
  // The outcome of the last execution: "completed", "cancelled: ...", "aborted: ..." or empty.
  const std::string& last_execution_result() const { return last_result_; }

  // [SECTION] registration capture (telear/session/capture_session.hpp, the console's
  // Registration panel): a CaptureSession on this session's robot client and on a vision client
  // of its own, at the cameras' own size and JPEG quality 100 (the live view may be reduced).
  // Opening needs the lease (nobody else moves the arm between the operator's poses); opening
  // again closes the previous capture, whose folder stays as it is on disk.
  Status open_capture(CaptureSessionOptions options);
  CaptureSession* capture() { return capture_.get(); }
  const CaptureSession* capture() const { return capture_.get(); }
  void close_capture();
  // An add started with CaptureSession::start_add_pose is appended by update() when done
  // (logged: the pose's summary, or why it was not added).

  // [SECTION] per frame
  // Advances the preview by dt (s), feeds the monitor, the display mode and the registration
  // check. Call once per displayed frame.
  void update(double dt);
  const SessionView& view() const { return view_; }
  SessionStats stats() const;
  // Glass to glass: what the UI read back from the frame buffer it drew view().frame into
  // (telear/render/frame_code_readback.hpp): the frame's id, its frame code (nullopt: none
  // readable) and when the read returned (this machine's monotonic_ns). The code's capture
  // time (server clock) is converted with the vision client's clock offset, like every stage.
  // A frame counts once, the first time it is drawn (shown_noted() tells the UI not to read it
  // again); a code of another frame number counts as none.
  void note_shown(std::uint64_t frame_id, const std::optional<vision::FrameCode>& code,
                  std::int64_t shown_ns);
  bool shown_noted(std::uint64_t frame_id) const { return frame_id == shown_frame_id_; }
  DisplayModeSelector& display() { return display_; }
  void set_injected_video_delay(double seconds) { options_.injected_video_delay_s = seconds; }
  void set_injected_state_delay(double seconds) { options_.injected_state_delay_s = seconds; }

  const std::deque<SessionEvent>& events() const { return events_; }
  // The live plots' series (telear/session/live_series.hpp), fed by update().
  const LiveSeries& live_series() const { return live_series_; }
  double now() const;  // session clock, s (monotonic)
  // When the last update() took the newest robot state from the client (core::monotonic_ns):
  // the view's time for a recording (session_recording.hpp).
  std::int64_t state_taken_ns() const { return state_taken_ns_; }

 private:
  Session(core::RobotModelPtr model, SessionOptions options);
  void log(SessionEvent::Kind kind, std::string message, WorkflowStep step = WorkflowStep::kNone,
           std::string plan_id = {}, std::string plan_hash = {});
  void update_frame(double now);
  void update_monitor();
  void update_registration(double now);
  void update_capture();
  void update_clearance(const Eigen::VectorXd& q, double gripper);
  std::optional<Eigen::VectorXd> real_q() const;
  // The robot's newest state as this session sees it: held back by injected_state_delay_s.
  std::optional<net::RobotStateSample> reported_state() const;
  void deliver_states(double now);

  core::RobotModelPtr model_;
  SessionOptions options_;
  std::unique_ptr<net::RobotClient> robot_;
  std::unique_ptr<net::VisionClient> vision_;
  bool connected_ = false;
  bool ghost_synced_ = false;  // the ghost starts where the real robot first reports itself
  std::optional<double> start_tolerance_;  // the server's, once GetInfo answered
  GhostArm ghost_;
  std::unique_ptr<geometry::CollisionChecker> checker_;  // null: no collision checking
  std::optional<GhostClearance> clearance_;
  Plan plan_;
  std::optional<PlanPreview> preview_;
  std::optional<ExecutionMonitor> monitor_;
  std::string executing_id_;
  std::string previewed_hash_, executed_hash_;
  bool executing_ = false;
  int executions_ = 0;
  std::string last_result_;
  DisplayModeSelector display_;
  std::optional<RegistrationCheck> registration_;
  double next_registration_check_ = 0.0;
  StereoResidual residual_;
  int residual_checks_ = 0;
  std::uint64_t frame_number_ = 0;
  std::deque<std::pair<std::uint64_t, std::shared_ptr<const net::DecodedStereoFrame>>> delayed_;
  std::deque<std::pair<double, std::shared_ptr<const net::DecodedStereoFrame>>> recent_frames_;
  StateHistory state_history_;  // the delivered states by capture time (s)
  // The last note_shown()'s frame; the session time of each and its capture -> shown (s;
  // nullopt: no code).
  std::uint64_t shown_frame_id_ = 0;
  std::deque<std::pair<double, std::optional<double>>> recent_shown_;
  std::deque<net::RobotStateSample> held_states_;  // received, not yet delivered (state delay)
  std::optional<net::RobotStateSample> delivered_state_;
  std::uint64_t state_sequence_ = 0;  // the newest state taken from the client
  std::int64_t state_taken_ns_ = 0;
  ArmPredictor predictor_;
  SessionView view_;
  std::deque<SessionEvent> events_;
  std::unique_ptr<net::VisionClient> capture_vision_;  // before capture_: outlives it
  std::unique_ptr<CaptureSession> capture_;
  std::int64_t epoch_ns_ = 0;
  LiveSeries live_series_;
};

}  // namespace telear::session
