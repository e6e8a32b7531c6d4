#include "telear/session/demo_workflow.hpp"

#include <chrono>
#include <filesystem>
#include <system_error>

#include "telear/core/angles.hpp"
#include "telear/core/arm_body.hpp"
#include "telear/core/marker_mount.hpp"
#include "telear/core/number_format.hpp"
#include "telear/core/robot_loader.hpp"
#include "telear/core/workspace.hpp"
#include "telear/geometry/robot_assets.hpp"
#include "telear/geometry/workspace_meshes.hpp"
#include "telear/render/ar_view.hpp"
#include "telear/render/egl_context.hpp"
#include "telear/session/calibration_pipeline.hpp"
#include "telear/session/demo_report.hpp"
#include "telear/session/embedded_servers.hpp"
#include "telear/session/session.hpp"
#include "telear/session/session_recorder.hpp"
#include "telear/vision/camera_file.hpp"

namespace telear::session {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

Status DemoOptions::validate() const {
  if (delay_ms < 0 || delay_ms > 5000) {
    return Error{"--delay-ms " + std::to_string(delay_ms) + " is outside 0..5000"};
  }
  if (!(fps >= 1 && fps <= 60)) return Error{"--fps must be in 1..60"};
  if (!(camera_fps > 0 && camera_fps <= 120)) return Error{"--camera-fps must be in (0, 120]"};
  if (width < 64 || height < 48 || width > 1920 || height > 1080) {
    return Error{"the resolution " + std::to_string(width) + "x" + std::to_string(height) +
                 " is outside 64x48 .. 1920x1080"};
  }
  if (out_dir.empty()) return Error{"--out: give the folder to write the report to"};
  return Status::Ok();
}

Result<DemoOutcome> run_demo(const DemoOptions& options, const DemoProgress& progress) {
  const auto demo_start = Clock::now();
  const auto step = [&](int n, const std::string& what) {
    if (progress.step) progress.step(n, what);
  };
  const auto note = [&](const std::string& text) {
    if (progress.note) progress.note(text);
  };
  if (Status s = options.validate(); !s) return s.error();
  std::error_code ec;
  std::filesystem::create_directories(options.out_dir, ec);
  if (ec) return Error{"cannot create --out '" + options.out_dir + "': " + ec.message()};
  const std::string resolution =
      std::to_string(options.width) + "x" + std::to_string(options.height);

  step(1, "calibrating the simulated stereo rig and registering the robot");
  CalibrationPipelineOptions pipeline;
  auto robot = geometry::load_robot_assets(
      {options.robot, options.tip, options.geometry.package_paths}, options.geometry);
  if (!robot) return robot.error();
  const core::RobotModelPtr model = robot->model();
  EmbeddedServersOptions server_options;
  server_options.rig = options.rig_file;
  if (Status s = serve_robot(server_options, robot->description); !s) return s.error();
  pipeline.rig_file = server_options.rig;
  pipeline.robot = options.robot;
  pipeline.tip = options.tip;
  pipeline.geometry = options.geometry;
  pipeline.cache_dir = options.cache_dir.empty() ? options.out_dir + "/cache" : options.cache_dir;
  pipeline.seed = options.seed;
  auto calibration = run_calibration_pipeline(pipeline);
  if (!calibration) return calibration.error();
  note(std::string(calibration->cached ? "cached in " : "written to ") + pipeline.cache_dir + " (" +
       core::format_number(calibration->seconds, "%.1f") + " s)");
  auto camera_file = vision::load_camera_file(calibration->registered_file);
  if (!camera_file || !camera_file->right) {
    return Error{"cannot load the registered calibration: " +
                 (camera_file ? std::string("not a stereo file") : camera_file.error().message)};
  }

  step(2, "starting the simulated robot server and vision server on loopback");
  server_options.calibration_file = calibration->registered_file;
  server_options.seed = options.seed;
  server_options.fps = options.camera_fps;
  if (auto ready = model->named_configuration("ready")) {
    server_options.initial_q = *ready;
  } else {
    // The PUMA: a ready pose away from the wrist singularity of qr (q5 = 0), parked beside
    // the table, turned 90 deg away from it, clear of the workspace. The plan is then the
    // turn to the table and the task, 7.4 s (at waist 0 the hand would start right above the
    // box, 6.3 s, and jogging that shorter motion would cost 88x the plan message rather than
    // issue 14's 100x: docs/demo.md).
    Eigen::VectorXd ready_deg(6);
    ready_deg << -90.0, 30.0, -120.0, 0.0, -45.0, 0.0;
    server_options.initial_q =
        ready_deg.unaryExpr([](double d) { return core::radians_from_degrees(d); });
  }
  auto servers = EmbeddedServers::create(model, server_options);
  if (!servers) return servers.error();
  note("robot server " + (*servers)->robot_address() + ", vision server " +
       (*servers)->vision_address());

  step(3, "connecting the session and taking the lease");
  SessionOptions session_options;
  session_options.robot.address = (*servers)->robot_address();
  session_options.robot.token = (*servers)->token();
  session_options.robot.client_name = "telear-demo";
  session_options.vision.client_name = "telear-demo";
  session_options.lease_heartbeat_s = 1.0;  // see SessionOptions::lease_heartbeat_s
  session_options.vision.address = (*servers)->vision_address();
  session_options.vision.width = options.width;
  session_options.vision.height = options.height;
  vision::StereoCameraModel cameras;
  cameras.left = vision::resized_camera(camera_file->left, options.width, options.height);
  cameras.right = vision::resized_camera(*camera_file->right, options.width, options.height);
  session_options.cameras = cameras;
  // The marker from the robot's marker file, the box from the operator's workspace file (the
  // same scene the simulated rig renders).
  auto marker = robot->marker();
  if (!marker) return marker.error();
  session_options.marker = GripperMarker{marker->id, marker->corners_flange()};
  auto workspace = geometry::load_workspace(core::default_workspace_file(robot->description.name));
  if (!workspace) return workspace.error();
  const core::WorkspaceObject* graspable = workspace->first_graspable();
  if (!graspable) return Error{"the workspace " + workspace->source + " has nothing to pick"};
  const Eigen::Vector3d box = graspable->T_base_object.translation();
  const double table_z = workspace->support_height(box.head<2>(), box.z());
  // The session checks every plan against this scene (the box carried included), and
  // run_demo_task first rehearses into the table (docs/demo.md, "Collision check").
  session_options.description = robot->description;
  session_options.workspace = *workspace;
  auto session_or = Session::create(model, session_options);
  if (!session_or) return session_or.error();
  Session& session = **session_or;
  session.connect();

  auto context = render::create_headless_context();
  if (!context) return Error{"no OpenGL context: " + context.error().message};
  const core::ArmBody arm_body = core::build_arm_body(robot->body);
  std::vector<render::SceneObject> objects = {render::make_floor(3.0f, 12)};
  for (render::SceneObject& o : render::workspace_scene_objects(*workspace)) {
    objects.push_back(std::move(o));
  }
  auto view = render::ArView::create(*model, arm_body, cameras, objects);
  if (!view) return view.error();
  SessionRecorder recorder(session, *view, {options.out_dir, options.fps, options.video});
  const render::ComposedSize size =
      render::composed_size(render::StereoLayout::kSideBySide, options.width, options.height);
  if (Status s = recorder.open_video(size.width, size.height); !s) return s.error();
  if (!recorder.recording().video_warning.empty())
    note("warning: " + recorder.recording().video_warning);

  DemoTaskInputs task;
  task.box_base_m = box;
  task.grip_in_link_m = arm_body.gripper ? Eigen::Vector3d(arm_body.gripper->centre.cast<double>())
                                         : Eigen::Vector3d::Zero();
  task.camera_base_m = cameras.left.T_cam_base.inverse().translation();
  task.fps = options.fps;
  task.delay_ms = options.delay_ms;
  task.table_surface_z_m = table_z;
  auto outcome = run_demo_task(session, recorder, task, progress);
  if (!outcome) return outcome.error();

  step(7, "writing the report");
  DemoFacts facts;
  facts.robot = robot->description.name;
  facts.dof = model->dof();
  facts.tip_link = robot->description.tip_link;
  facts.calibration_json = calibration->evaluation.json;
  facts.calibration_cached = calibration->cached;
  facts.recording = recorder.recording();
  facts.resolution = resolution;
  facts.camera_fps = options.camera_fps;
  facts.video_bytes_per_s = session.stats().video_bytes_per_s;
  facts.plan_bytes_measured = outcome->plan_bytes_measured;
  facts.plan_message_bytes = outcome->plan_message_bytes;
  facts.previewed_hash = outcome->previewed_hash;
  facts.executed_hash = outcome->executed_hash;
  facts.bytes = outcome->bytes;
  facts.execution_result = outcome->execution_result;
  if (const ExecutionMonitor* monitor = session.monitor()) {
    facts.tracking = monitor->status();
    facts.tolerance_rad = monitor->options().tolerance;
  }
  facts.plan_duration_s = outcome->plan_duration_s;
  facts.waypoints = outcome->waypoints;
  facts.first_rehearsal_check = outcome->first_rehearsal_check;
  facts.final_plan_check = outcome->final_plan_check;
  facts.ar_to_vr = session.display().ar_to_vr_switches();
  facts.vr_to_ar = session.display().vr_to_ar_switches();
  facts.switches = session.display().switches();
  facts.injected_delay_ms = options.delay_ms;
  facts.seconds = seconds_since(demo_start);
  if (Status s = write_demo_report(facts, options.out_dir); !s) return s.error();

  session.disconnect();
  (*servers)->stop();
  DemoOutcome result;
  result.execution_result = outcome->execution_result;
  result.report_md = options.out_dir + "/report.md";
  result.report_json = options.out_dir + "/report.json";
  result.video_path = facts.recording.video_path;
  result.video_codec = facts.recording.video_codec;
  result.video_warning = facts.recording.video_warning;
  result.key_frames = facts.recording.key_frames;
  result.calibration_cached = calibration->cached;
  result.seconds = seconds_since(demo_start);
  return result;
}

}  // namespace telear::session
