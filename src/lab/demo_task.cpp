#include "telear/lab/demo_task.hpp"

#include <algorithm>
#include <chrono>
#include <memory>
#include <optional>
#include <thread>
#include <utility>

#include "telear/core/clock.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/number_format.hpp"

namespace telear::lab {
namespace {

using Clock = std::chrono::steady_clock;

constexpr double kMaxLift_m = 0.015;  // the most a step is raised off the table
// A step closer than this to the workspace is raised (touching is not a clearance).
constexpr double kMinStepClearance_m = 0.008;
// The predicted arm's key frame: its tool this far from the delayed arm's, so that both show.
constexpr double kPredictedKeyFrameSeparation_m = 0.1;

Error phase_error(const std::string& phase, const std::string& message) {
  return Error{phase + ": " + message};
}

// Waits for the first state and frame, takes the lease, shows a second of video.
Status start(session::Session& session, SessionRecorder& recorder, const DemoTaskInputs& inputs) {
  const auto wait_start = Clock::now();
  while (!(session.view().real && session.view().frame)) {
    if (core::seconds_since(wait_start) > inputs.connect_timeout_s) {
      return Error{"no robot state or video from the servers after " +
                   core::format_number(inputs.connect_timeout_s) + " s"};
    }
    session.update(0.02);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (Status s = session.take_control(); !s) return s;
  recorder.ticks(static_cast<int>(inputs.fps));
  if (auto k = recorder.key_frame("keyframe_1_start"); !k) return k.error();
  return Status::Ok();
}

// The rehearsal that goes wrong: start, above the box, then down through the table top beside
// it. Validation must fail on the contact; the preview is stopped just inside it for the key
// frame, then the plan is discarded. Returns the plan's collision check.
Result<geometry::TrajectoryCheckReport> rehearse_into_the_table(
    session::Session& session, SessionRecorder& recorder, const DemoTaskInputs& inputs,
    const GraspChoice& grasp, const std::function<void(const std::string&)>& note) {
  const core::RobotModel& model = session.model();
  const Eigen::Vector3d beside = inputs.box_base_m + Eigen::Vector3d(0.0, -0.1, 0.0);
  const Eigen::Vector3d above(beside.x(), beside.y(), inputs.box_base_m.z() + 0.12);
  const Eigen::Vector3d into(beside.x(), beside.y(), inputs.table_surface_z_m - 0.05);
  if (Status s = session.add_ghost_waypoint(0.0, "start"); !s) return s.error();
  for (const auto& [label, position] : {std::pair{"above the table", above}, {"down", into}}) {
    const core::MotionOutcome moved = session.move_ghost(
        core::CartesianTarget{grasp.T_base_tool(model, inputs.grip_in_link_m, position)});
    if (!moved.accepted) return Error{std::string(label) + ": " + moved.rejection.message};
    if (Status s = session.add_ghost_waypoint(0.0, label); !s) return s.error();
    recorder.ticks(static_cast<int>(inputs.fps / 3));
  }
  const session::ValidationReport validation = session.validate_plan();
  note("validation of the first rehearsal: " + validation.summary());
  if (!validation.collision) return Error{"the plan was not checked for collisions"};
  const geometry::TrajectoryCheckReport check = *validation.collision;
  if (!check.collision_free()) {
    // Just inside the contact (its start is where the surfaces meet: nothing to see yet).
    const geometry::PlanCollision& first = check.collisions.front();
    if (Status s = session.start_preview({.loop = false, .speed = 1.0}); !s) return s.error();
    session.preview()->seek(std::min(first.time_s + 0.15, session.preview()->duration()));
    session.preview()->pause();
    recorder.ticks(static_cast<int>(inputs.fps / 2));
    note("contact shown: " + session.ghost_clearance().summary());
    if (auto k = recorder.key_frame("keyframe_2a_collision"); !k) return k.error();
    session.stop_preview();
  }
  session.plan().clear();
  if (Status s = session.ghost_to_real(); !s) return s.error();
  return check;
}

}  // namespace

std::vector<TaskStep> pick_and_place_steps(const Eigen::Vector3d& box_base_m,
                                           const Eigen::Vector3d& place_base_m) {
  const Eigen::Vector3d up(0, 0, 0.12);
  return {
      {"approach", box_base_m + up, 1.0, 0.0},
      {"grasp", box_base_m, 0.0, 1.2},
      {"lift", box_base_m + up, std::nullopt, 0.0},
      {"carry", place_base_m + up, std::nullopt, 0.0},
      {"place", place_base_m, 1.0, 1.2},
      {"retreat", place_base_m + up, std::nullopt, 0.0},
  };
}

std::vector<TaskStep> demo_task_steps(const DemoTaskInputs& inputs) {
  return pick_and_place_steps(inputs.box_base_m, inputs.box_base_m + inputs.place_offset_m);
}

Result<GraspChoice> choose_task_grasp(const session::Session& session,
                                      const DemoTaskInputs& inputs) {
  GraspRequest request;
  for (const TaskStep& s : demo_task_steps(inputs))
    request.grip_positions_base_m.push_back(s.grip_position_base_m);
  request.grip_in_link_m = inputs.grip_in_link_m;
  request.q_start = session.ghost().q();
  request.camera_base_m = inputs.camera_base_m;
  const session::SessionOptions& options = session.options();
  if (session.checks_collisions() && options.description && options.workspace) {
    // The session's scene, the graspable objects left out as the session does (the fingers
    // close on the box on purpose). Contacts the rehearsal lifts the step out of (a known
    // depth under kMaxLift_m: the fingertips below the box's bottom) do not count.
    core::Workspace obstacles = *options.workspace;
    std::erase_if(obstacles.objects, [](const core::WorkspaceObject& o) { return o.graspable; });
    geometry::CollisionSetupOptions setup;
    setup.mesh_collision = options.mesh_collision;
    auto made = geometry::make_collision_checker(*options.description, obstacles, setup);
    if (!made) return Error{"choose the grasp: collision checker: " + made.error().message};
    auto checker = std::make_shared<geometry::CollisionChecker>(std::move(*made));
    request.contact = [checker](const Eigen::VectorXd& q) -> std::optional<std::string> {
      for (const geometry::Contact& c : checker->check(q).contacts) {
        if (c.depth_m > 0.0 && c.depth_m < kMaxLift_m) continue;
        return c.body + " and " + c.other + " (" + core::format_number(c.depth_m * 1e3, "%.1f") +
               " mm deep)";
      }
      return std::nullopt;
    };
  }
  return choose_grasp(session.model(), request);
}

Status rehearse_pick_and_place(session::Session& session, const DemoTaskInputs& inputs,
                               const GraspChoice& grasp, const DemoProgress& progress,
                               const std::function<Status(const TaskStep&)>& after_step) {
  const auto note = [&](const std::string& text) {
    if (progress.note) progress.note(text);
  };
  const core::RobotModel& model = session.model();
  session.plan().clear();
  if (Status s = session.add_ghost_waypoint(0.0, "start"); !s)
    return phase_error("rehearsal", s.error().message);
  for (const TaskStep& task : demo_task_steps(inputs)) {
    const core::MotionOutcome moved = session.move_ghost(core::CartesianTarget{
        grasp.T_base_tool(model, inputs.grip_in_link_m, task.grip_position_base_m)});
    if (!moved.accepted) return phase_error("rehearsal: " + task.label, moved.rejection.message);
    // The correction the first rehearsal taught: where the ghost touches the table or grazes
    // it (the fingertips reach below the box's bottom: 5 mm on the PUMA), raise it 5 mm at a
    // time, as an operator watching the clearance would, within the grasp model's 2 cm
    // capture distance.
    const auto too_close = [&] {
      const session::ClearanceState& c = session.ghost_clearance();
      return c.level == session::ClearanceState::Level::kContact ||
             (c.level == session::ClearanceState::Level::kWithinMargin &&
              c.workspace.distance_m < kMinStepClearance_m);
    };
    for (double lift = 0.005; too_close() && lift <= kMaxLift_m + 1e-9; lift += 0.005) {
      const core::MotionOutcome raised = session.move_ghost(core::CartesianTarget{
          grasp.T_base_tool(model, inputs.grip_in_link_m,
                            task.grip_position_base_m + Eigen::Vector3d(0.0, 0.0, lift))});
      if (!raised.accepted) break;
      note(task.label + ": raised " + core::format_number(lift * 1e3, "%.0f") +
           " mm off the table (" + session.ghost_clearance().summary() + ")");
    }
    if (task.gripper) (void)session.ghost().set_gripper(*task.gripper);
    if (Status s = session.add_ghost_waypoint(0.0, task.label); !s)
      return phase_error("rehearsal: " + task.label, s.error().message);
    if (task.dwell_s > 0) (void)session.add_ghost_waypoint(task.dwell_s, task.label + " (dwell)");
    if (after_step) {
      if (Status s = after_step(task); !s) return phase_error("rehearsal", s.error().message);
    }
  }
  return Status::Ok();
}

Result<DemoTaskOutcome> run_demo_task(session::Session& session, SessionRecorder& recorder,
                                      const DemoTaskInputs& inputs, const DemoProgress& progress) {
  const auto step = [&](int n, const std::string& what) {
    if (progress.step) progress.step(n, what);
  };
  const auto note = [&](const std::string& text) {
    if (progress.note) progress.note(text);
  };
  if (Status s = start(session, recorder, inputs); !s)
    return phase_error("start", s.error().message);
  DemoTaskOutcome outcome;

  // Rehearsal.
  step(4, "rehearsing the pick-and-place on the ghost");
  if (Status s = session.ghost_to_real(); !s) return phase_error("rehearsal", s.error().message);
  auto grasp = choose_task_grasp(session, inputs);
  if (!grasp) return phase_error("rehearsal", grasp.error().message);
  outcome.grasp = *grasp;
  note("grasp: " + grasp->note());
  (void)session.plan().set_scales(0.5, 0.5);
  if (session.checks_collisions()) {
    auto check = rehearse_into_the_table(session, recorder, inputs, *grasp, note);
    if (!check) return phase_error("rehearsal: into the table", check.error().message);
    outcome.first_rehearsal_check = std::move(*check);
  }
  auto rehearsed = rehearse_pick_and_place(
      session, inputs, *grasp, progress, [&](const TaskStep& task) -> Status {
        recorder.ticks(static_cast<int>(inputs.fps / 3));
        if (task.label != "grasp") return Status::Ok();
        auto k = recorder.key_frame("keyframe_2_rehearsal_grasp");
        if (!k) return k.error();
        return Status::Ok();
      });
  if (!rehearsed) return rehearsed.error();
  auto trajectory = session.plan().trajectory();
  if (!trajectory) return phase_error("rehearsal", trajectory.error().message);
  outcome.waypoints = static_cast<int>(session.plan().size());
  outcome.plan_duration_s = trajectory->duration();
  note(std::to_string(outcome.waypoints) + " waypoints, " +
       core::format_number(outcome.plan_duration_s, "%.2f") + " s");

  // Preview.
  step(5, "previewing the plan on the ghost over the live video");
  if (Status s = session.start_preview({.loop = false, .speed = 2.0}); !s)
    return phase_error("preview", s.error().message);
  bool preview_key = false;
  while (session.preview() && !session.preview()->current().at_end) {
    recorder.tick();
    if (!preview_key && session.preview()->time() > 0.45 * outcome.plan_duration_s) {
      if (auto k = recorder.key_frame("keyframe_3_preview"); !k)
        return phase_error("preview", k.error().message);
      preview_key = true;
    }
  }
  session.stop_preview();
  (void)session.ghost_to_real();

  // Execution.
  step(6, "validating, executing on the robot and monitoring");
  const session::ValidationReport validation = session.validate_plan();
  outcome.validation_summary = validation.summary();
  outcome.final_plan_check = validation.collision;
  note("validation: " + outcome.validation_summary);
  if (!validation.ok())
    return phase_error("execution", "the plan is not valid: " + outcome.validation_summary);
  const std::uint64_t bytes_before = session.robot().command_bytes_sent();
  auto ack = session.execute_plan();
  if (!ack) return phase_error("execution", ack.error().message);
  outcome.plan_bytes_measured = session.robot().command_bytes_sent() - bytes_before;
  const auto exec_start = Clock::now();
  const double duration = outcome.plan_duration_s;
  const double delay_s = inputs.delay_ms / 1000.0;
  bool execution_key = false, vr_key = false, predicted_key = false;
  PredictionErrorSeries prediction(session.model());
  // The delay window (issue 23, predict first): from 40 % of the plan the whole link is late
  // (video and states): the view stays in AR, the arm predicted over the late video. The plan
  // over (as the late states tell), prediction is impossible: the video, still late, switches
  // the view to VR for kLateAfterPlan_s; then the delay ends and the view returns to AR.
  constexpr double kLateAfterPlan_s = 1.0;
  std::optional<double> ended_at;  // t when the session saw the plan end
  while (true) {
    const double t = core::seconds_since(exec_start);
    if (t > duration + 30) return phase_error("execution", "the execution did not finish in time");
    if (!session.executing() && !ended_at) ended_at = t;
    if (ended_at && (delay_s == 0.0 || t >= *ended_at + kLateAfterPlan_s)) break;
    const bool in_window = delay_s > 0.0 && t > 0.4 * duration;
    session.set_injected_video_delay(in_window ? delay_s : 0.0);
    // The states only while the plan runs: after it the arm rests, and the VR key frame is
    // drawn from the states as received (a recording holds those, not the held-back ones).
    const bool states_late = in_window && !ended_at;
    session.set_injected_state_delay(states_late ? delay_s : 0.0);
    // The truth just before the view's update: the prediction is for that moment.
    const Eigen::VectorXd truth =
        states_late && inputs.true_q ? inputs.true_q() : Eigen::VectorXd();
    recorder.tick();
    const session::SessionView& view = session.view();
    if (truth.size() > 0) prediction.add(view, truth);
    if (!predicted_key && states_late && view.show_prediction && view.real &&
        (core::tool_pose(session.model(), view.prediction.q).translation() -
         core::tool_pose(session.model(), view.real->state.q).translation())
                .norm() >= kPredictedKeyFrameSeparation_m) {
      if (auto k = recorder.key_frame("keyframe_5b_predicted"); !k)
        return phase_error("execution", k.error().message);
      predicted_key = true;
    }
    if (!execution_key && t > 0.3 * duration) {
      if (auto k = recorder.key_frame("keyframe_4_execution"); !k)
        return phase_error("execution", k.error().message);
      execution_key = true;
    }
    if (!vr_key && ended_at && session.view().display.mode == session::DisplayMode::kVR) {
      if (auto k = recorder.key_frame("keyframe_5_vr_while_video_late"); !k)
        return phase_error("execution", k.error().message);
      vr_key = true;
    }
  }
  session.set_injected_video_delay(0.0);
  session.set_injected_state_delay(0.0);
  if (prediction.frames() > 0) outcome.prediction = prediction.summary();
  recorder.ticks(static_cast<int>(inputs.fps * 1.5));
  if (auto k = recorder.key_frame("keyframe_6_done"); !k)
    return phase_error("execution", k.error().message);
  recorder.close_video();
  outcome.execution_result = session.last_execution_result();
  note("execution: " + outcome.execution_result);

  // The same motion's cost as the plan message, as its 100 Hz samples in one message, and as
  // 100 Hz jogs (a lease id of the server's length, an id of the session's form).
  const std::string lease(32, '0'), id = "plan-0000000000-1";
  auto samples = trajectory->sampled(100.0);
  if (!samples) return phase_error("execution", samples.error().message);
  outcome.bytes = net::compare_command_bytes(*samples, 100.0, lease, id);
  auto message = net::plan_message_bytes(*trajectory, lease, id);
  if (!message) return phase_error("execution", message.error().message);
  outcome.plan_message_bytes = *message;
  outcome.previewed_hash = session.previewed_hash();
  outcome.executed_hash = session.executed_hash();
  return outcome;
}

}  // namespace telear::lab
