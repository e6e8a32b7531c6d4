#pragma once
// The demo's task on a connected session::Session (docs/demo.md, steps 3-6): take the lease,
// rehearse a pick-and-place on the ghost into a plan, preview it, then validate, execute and
// monitor it with a window of injected video delay, recording every display tick and the key frames
// through a SessionRecorder (include/telear/lab/session_recorder.hpp).
//
// With a collision-checking session (session::SessionOptions::description and workspace) a first
// rehearsal goes wrong on purpose: from above the box the gripper is lowered 5 cm into the
// table top, 0.1 m along -y of the box; validation fails naming the contact, the preview is
// stopped just after the contact starts (the links in contact are drawn red: key frame
// keyframe_2a_collision), and that plan is discarded. While the real task is rehearsed, a step
// where the ghost touches something, or comes within 8 mm of it, is raised 5 mm at a time (up
// to 15 mm).
//
// The task: approach 0.12 m above the box, grasp (close the gripper, dwell 1.2 s), lift, carry
// to 0.2 m along -y of the base, place (open, dwell 1.2 s), retreat 0.12 m up; the gripper's
// rotation is chosen once for all steps (include/telear/lab/grasp_choice.hpp). The plan is
// timed at half the arm's speed and acceleration limits, previewed at 2x; during execution,
// from 40 % of the plan's duration for 3 s, the video is held back by `delay_ms` (the display
// switches to VR and back), and from the first VR frame to the window's end the robot's states
// too (the whole link late): the view draws the predicted arm (session::ArmPredictor), measured
// against the simulator's truth when `true_q` is given. Key frames: keyframe_1_start,
// keyframe_2a_collision (with a checker), keyframe_2_rehearsal_grasp, keyframe_3_preview,
// keyframe_4_execution, keyframe_5_vr_while_video_late (when VR was shown),
// keyframe_5b_predicted (the predicted arm 10 cm or more from the delayed one), keyframe_6_done.
// Runs on the recorder's (OpenGL) thread; seconds of wall time.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/lab/grasp_choice.hpp"
#include "telear/lab/prediction_error.hpp"
#include "telear/lab/session_recorder.hpp"
#include "telear/net/command_bytes.hpp"
#include "telear/session/session.hpp"

namespace telear::lab {

// Progress for a terminal: step(n, what) at each numbered step, note(text) for its details.
struct DemoProgress {
  std::function<void(int step, const std::string& what)> step;
  std::function<void(const std::string& text)> note;
};

struct TaskStep {
  std::string label;
  Eigen::Vector3d grip_position_base_m;
  std::optional<double> gripper;  // opening on arrival, 0..1
  double dwell_s = 0.0;           // at the pose after arrival (a repeated waypoint)
};

// The six steps of the pick-and-place from `box` to `place` (base frame, m).
std::vector<TaskStep> pick_and_place_steps(const Eigen::Vector3d& box_base_m,
                                           const Eigen::Vector3d& place_base_m);

struct DemoTaskInputs {
  Eigen::Vector3d box_base_m = Eigen::Vector3d::Zero();      // the object's centre
  Eigen::Vector3d grip_in_link_m = Eigen::Vector3d::Zero();  // the gripper's centre in link 6
  Eigen::Vector3d camera_base_m = Eigen::Vector3d::Zero();   // the left camera's centre
  double fps = 15.0;                                         // the recorder's tick rate
  int delay_ms = 400;  // injected video (then state) delay; 0: none
  // The simulated arm's true joints now (EmbeddedServers' robot), for the predicted arm's error
  // during the delay; empty: not measured.
  std::function<Eigen::VectorXd()> true_q;
  double connect_timeout_s = 30.0;  // for the first robot state and video frame
  // Height (base z) of the table's top under the box: the first rehearsal, when the session
  // checks collisions, lowers the gripper 5 cm below it.
  double table_surface_z_m = 0.0;
  // Where the box is put down, from where it is picked up (base frame, m).
  Eigen::Vector3d place_offset_m = Eigen::Vector3d(0.0, -0.2, 0.0);
};

struct DemoTaskOutcome {
  GraspChoice grasp;
  int waypoints = 0;
  double plan_duration_s = 0.0;
  std::string validation_summary;
  std::uint64_t plan_bytes_measured = 0;  // what execute_plan sent (the plan message)
  std::uint64_t plan_message_bytes = 0;   // the same message's size, computed
  net::CommandBytes bytes;       // 100 Hz samples (one message) vs 100 Hz jogs of the same motion
  std::string previewed_hash;    // the plan_hash of the trajectory the preview showed
  std::string executed_hash;     // the robot server's hash of the trajectory it ran
  std::string execution_result;  // session::Session::last_execution_result()
  // With a collision-checking session: the first rehearsal's check (into the table) and the
  // executed plan's.
  std::optional<geometry::TrajectoryCheckReport> first_rehearsal_check;
  std::optional<geometry::TrajectoryCheckReport> final_plan_check;
  // The tool drawn against the truth while the states were late (with inputs.true_q).
  std::optional<PredictionErrorSummary> prediction;
};

// The task's steps for these inputs: the box, and the place 0.2 m along -y of it.
std::vector<TaskStep> demo_task_steps(const DemoTaskInputs& inputs);

// The grasp for the task's steps from where the ghost is (include/telear/lab/grasp_choice.hpp).
// On a collision-checking session an orientation whose IK branch touches the scene at a step
// is passed over (contacts of a known depth under the 15 mm the rehearsal lifts excepted), and
// when every one does the error names the first contact.
Result<GraspChoice> choose_task_grasp(const session::Session& session,
                                      const DemoTaskInputs& inputs);

// Rehearses the task on the ghost, from where it is, into the session's plan (cleared first):
// a "start" waypoint, then each step's pose (raised 5 mm at a time, up to 15 mm, where the
// ghost touches something or comes within 8 mm of it), its gripper and dwell. `after_step` runs
// after each step (the demo's recorder ticks and key frame). It needs no server: tests rehearse
// offline.
Status rehearse_pick_and_place(session::Session& session, const DemoTaskInputs& inputs,
                               const GraspChoice& grasp, const DemoProgress& progress = {},
                               const std::function<Status(const TaskStep&)>& after_step = {});

// Errors name the phase ("start", "rehearsal: grasp", "preview", "execution") and the
// session's reason. The step callbacks are numbered 4..6 (the demo's 7 steps).
Result<DemoTaskOutcome> run_demo_task(session::Session& session, SessionRecorder& recorder,
                                      const DemoTaskInputs& inputs,
                                      const DemoProgress& progress = {});

}  // namespace telear::lab
