#include "telear/lab/demo_workflow.hpp"

#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <system_error>

#include "telear/core/angles.hpp"
#include "telear/core/arm_body.hpp"
#include "telear/core/clock.hpp"
#include "telear/core/image_size.hpp"
#include "telear/core/marker_mount.hpp"
#include "telear/core/number_format.hpp"
#include "telear/core/robot_loader.hpp"
#include "telear/core/version.hpp"
#include "telear/core/workspace.hpp"
#include "telear/geometry/robot_assets.hpp"
#include "telear/geometry/workspace_meshes.hpp"
#include "telear/lab/calibration_pipeline.hpp"
#include "telear/lab/capture_start.hpp"
#include "telear/lab/demo_report.hpp"
#include "telear/lab/embedded_servers.hpp"
#include "telear/lab/session_recorder.hpp"
#include "telear/record/mcap_reader.hpp"
#include "telear/record/server_recorder.hpp"
#include "telear/render/ar_view.hpp"
#include "telear/render/egl_context.hpp"
#include "telear/report/recording_report.hpp"
#include "telear/session/registration_capture.hpp"
#include "telear/session/session.hpp"
#include "telear/session/session_recording.hpp"
#include "telear/sim/stereo_rig.hpp"
#include "telear/vision/accuracy_check.hpp"
#include "telear/vision/calibration_file.hpp"
#include "telear/vision/camera_file.hpp"
#include "telear/vision/capture_registration.hpp"
#include "telear/vision/observations_file.hpp"
#include "telear/vision/overlay_accuracy.hpp"
#include "telear/vision/registered_camera_file.hpp"

namespace telear::lab {
namespace {

using Clock = std::chrono::steady_clock;

struct ServerRegistration {
  vision::StereoCameraModel cameras;  // the intrinsics served, T_cam_base registered
  std::string eval_json;              // against the simulator's truth (telear eval's JSON)
  std::string json;                   // the report's "registration" object
};

// Registration through the servers (docs/registration.md, "Register your real cameras"):
// capture at automatic poses around the start, detect the marker in the saved images, solve
// the hand-eye registration, and measure it against the rig's true cameras.
Result<ServerRegistration> register_through_servers(
    const core::RobotModel& model, const core::ArmBody& body, const core::MarkerMount& marker,
    const core::Workspace& workspace, const EmbeddedServers& servers,
    const vision::StereoCameraModel& truth, const std::string& truth_file,
    const Eigen::VectorXd& finish, const std::string& directory, const DemoOptions& options,
    const std::function<void(const std::string&)>& note) {
  const auto start = Clock::now();
  std::error_code ec;
  std::filesystem::remove_all(directory, ec);  // a fresh capture every run
  net::RobotClientOptions robot_options;
  robot_options.address = servers.robot_address();
  robot_options.token = servers.token();
  robot_options.client_name = "telear-demo-capture";
  net::RobotClient robot(robot_options);
  robot.start();
  net::VisionClientOptions vision_options;
  vision_options.address = servers.vision_address();
  vision_options.token = servers.token();
  vision_options.client_name = "telear-demo-capture";
  vision_options.jpeg_quality = 100;  // the least loss the stream offers
  net::VisionClient vision(vision_options);
  vision.start();
  // A 1 s heartbeat as the session::Session asks for: this machine also renders both cameras.
  if (Status s = robot.acquire_lease(1.0); !s) return Error{"capture: lease: " + s.error().message};
  session::RegistrationCaptureOptions capture;
  capture.directory = directory;
  capture.auto_poses = options.registration_poses;
  capture.frames_per_pose = options.registration_frames;
  capture.seed = options.seed;
  capture.velocity_scale = 1.0;
  capture.settle_s = 0.1;
  capture.marker = marker;
  capture.body = body;
  capture.workspace = workspace;
  capture.finish_pose = finish;
  auto captured = session::capture_for_registration(model, robot, vision, capture);
  (void)robot.release_lease();
  if (!captured) return captured.error();
  const double capture_s = core::seconds_since(start);
  auto registration = vision::register_captures(model, directory, "", marker);
  if (!registration) return Error{"register: " + registration.error().message};
  const vision::HandEyeResult& r = registration->result;
  ServerRegistration out;
  out.cameras = registration->registered;
  const vision::AccuracyReport accuracy =
      vision::evaluate_accuracy(model, body, truth, out.cameras);
  out.eval_json = vision::accuracy_report_json(accuracy, vision::accuracy_checks(accuracy));
  nlohmann::json json;
  json["path"] = "capture through the servers";
  json["capture_dir"] = directory;
  json["poses_requested"] = options.registration_poses;
  json["poses_captured"] = static_cast<int>(captured->capture.poses.size());
  json["poses_used"] = r.views_used;
  json["frames_per_pose"] = options.registration_frames;
  json["capture_s"] = capture_s;
  json["seconds"] = core::seconds_since(start);
  for (auto [eye, e, baseline, t] :
       {std::tuple{"left", &accuracy.left, &r.baseline_left, &truth.left},
        std::tuple{"right", &accuracy.right, &r.baseline_right, &truth.right}}) {
    nlohmann::json j;
    j["registration_mm"] = e->registration.position_mm;
    j["registration_deg"] = e->registration.rotation_deg;
    j["overlay_rms_px"] = e->overlay.rms_px;
    if (baseline->solved) {
      const vision::PoseError shah_li =
          vision::registration_error(t->T_cam_base, baseline->T_cam_base);
      j["shah_li_mm"] = shah_li.position_mm;
      j["shah_li_deg"] = shah_li.rotation_deg;
    }
    json[eye] = j;
  }
  // The same captures solved with the rig's true intrinsics and stereo geometry: the
  // registration's own error, apart from the chessboard calibration's (its focal length error
  // moves the camera centre along the optical axis).
  if (auto exact = vision::register_captures(model, directory, truth_file, marker)) {
    for (auto [eye, t, estimate] :
         {std::tuple{"left", &truth.left, &exact->result.T_left_base},
          std::tuple{"right", &truth.right, &exact->result.T_right_base}}) {
      const vision::PoseError e = vision::registration_error(t->T_cam_base, *estimate);
      json["true_intrinsics"][eye] = {{"registration_mm", e.position_mm},
                                      {"registration_deg", e.rotation_deg}};
    }
  }
  json["sigma_mm"] = r.base_sigma.position_mm;
  json["sigma_deg"] = r.base_sigma.rotation_deg;
  out.json = json.dump();
  note("registered from " + std::to_string(r.views_used) + " of " +
       std::to_string(captured->capture.poses.size()) + " poses captured through the servers (" +
       core::format_number(capture_s, "%.1f") + " s): left " +
       core::format_number(accuracy.left.registration.position_mm, "%.3f") + " mm " +
       core::format_number(accuracy.left.registration.rotation_deg, "%.4f") + " deg, right " +
       core::format_number(accuracy.right.registration.position_mm, "%.3f") + " mm " +
       core::format_number(accuracy.right.registration.rotation_deg, "%.4f") +
       " deg against the simulator's truth");
  if (json.contains("true_intrinsics")) {
    const nlohmann::json& t = json["true_intrinsics"];
    note("the same captures with the rig's true intrinsics: left " +
         core::format_number(t["left"]["registration_mm"].get<double>(), "%.3f") + " mm, right " +
         core::format_number(t["right"]["registration_mm"].get<double>(), "%.3f") +
         " mm (the rest is the chessboard calibration's focal length error)");
  }
  // The registered pair beside the capture, as `telear register --captures` writes it.
  if (Status s = vision::write_files_atomically(
          {{directory + "/registered.yaml",
            vision::registered_camera_yaml(out.cameras, registration->T_right_left)}});
      !s) {
    return s.error();
  }
  return out;
}

}  // namespace

Status DemoOptions::validate() const {
  if (delay_ms < 0 || delay_ms > 5000) {
    return Error{"delay_ms " + std::to_string(delay_ms) + " is outside 0..5000"};
  }
  if (!(fps >= 1 && fps <= 60)) return Error{"fps must be in 1..60"};
  if (!(camera_fps > 0 && camera_fps <= 120)) return Error{"camera_fps must be in (0, 120]"};
  if (width < 64 || height < 48 || width > 1920 || height > 1080) {
    return Error{"the resolution " + core::to_string(core::ImageSize{width, height}) +
                 " is outside 64x48 .. 1920x1080"};
  }
  if (out_dir.empty()) return Error{"out_dir: give the folder to write the report to"};
  if (registration_poses < 4 || registration_poses > 200) {
    return Error{"the registration poses " + std::to_string(registration_poses) +
                 " are outside 4..200"};
  }
  if (registration_frames < 1 || registration_frames > 30) {
    return Error{"the registration frames " + std::to_string(registration_frames) +
                 " are outside 1..30"};
  }
  if (supersample < 1 || supersample > 8) {
    return Error{"the supersampling " + std::to_string(supersample) + " is outside 1..8"};
  }
  if (live_multisample < 1 || live_multisample > 16) {
    return Error{"the live video's multisampling " + std::to_string(live_multisample) +
                 " is outside 1..16"};
  }
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
  if (ec)
    return Error{"cannot create the output folder '" + options.out_dir + "': " + ec.message()};
  const std::string resolution = core::to_string(core::ImageSize{options.width, options.height});

  step(1, "calibrating the simulated stereo rig");
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
  // The pipeline's stereo calibration (intrinsics and the pair's geometry) is what the vision
  // server serves; the robot is registered below from images captured through the servers.
  const std::string stereo_file = pipeline.cache_dir + "/stereo.yaml";
  auto truth = sim::load_stereo_rig(server_options.rig);
  if (!truth) return truth.error();
  auto marker = robot->marker();
  if (!marker) return marker.error();
  auto workspace = geometry::load_workspace(core::default_workspace_file(robot->description.name));
  if (!workspace) return workspace.error();
  const core::ArmBody arm_body = core::build_arm_body(robot->body);

  step(2, "starting the simulated robot and vision servers on loopback, registering through them");
  server_options.calibration_file = stereo_file;
  server_options.seed = options.seed;
  server_options.fps = options.camera_fps;
  server_options.supersample = options.supersample;
  // With MSAA as well: 2 x 2 samples alone put a nearly level edge of the marker on a staircase
  // of half pixels, its corners 0.2-0.35 px off in such views (issue 26 item 1).
  server_options.multisample = options.live_multisample;
  Eigen::VectorXd ready_q;
  if (auto ready = model->named_configuration("ready")) {
    ready_q = *ready;
  } else {
    // The PUMA: a ready pose away from the wrist singularity of qr (q5 = 0), parked beside
    // the table, turned 90 deg away from it, clear of the workspace. The plan is then the
    // turn to the table and the task, 7.4 s (at waist 0 the hand would start right above the
    // box, 6.3 s, and jogging that shorter motion would cost 88x the plan message rather than
    // issue 14's 100x: docs/demo.md).
    Eigen::VectorXd ready_deg(6);
    ready_deg << -90.0, 30.0, -120.0, 0.0, -45.0, 0.0;
    ready_q = ready_deg.unaryExpr([](double d) { return core::radians_from_degrees(d); });
  }
  // The arm starts where both cameras see its marker (the operator's jog before capturing);
  // the capture ends at the ready pose the task starts from. The capture's cameras render
  // with options.supersample (finer corners).
  auto observations = vision::load_observations_file(pipeline.cache_dir + "/observations.yaml");
  if (!observations) return observations.error();
  auto capture_start = capture_start_pose(*observations, robot->description, *workspace, ready_q);
  if (!capture_start) return capture_start.error();
  server_options.initial_q = *capture_start;
  auto servers = EmbeddedServers::create(model, server_options);
  if (!servers) return servers.error();
  note("robot server " + (*servers)->robot_address() + ", vision server " +
       (*servers)->vision_address());
  auto registration =
      register_through_servers(*model, arm_body, *marker, *workspace, **servers, truth->cameras,
                               pipeline.cache_dir + "/capture/truth.yaml", ready_q,
                               options.out_dir + "/registration_capture", options, note);
  if (!registration)
    return Error{"registration through the servers: " + registration.error().message};
  // The task's servers: the same simulated robot and rig, restarted at the ready pose where
  // the capture left the arm, their cameras rendered at the live view's cost (anti-aliasing 1:
  // the video's frames must stay fresh on a 2-core machine, or the view stays in VR).
  (*servers)->stop();
  servers->reset();
  server_options.initial_q = ready_q;
  server_options.supersample = 1;
  server_options.multisample = options.live_multisample;
  servers = EmbeddedServers::create(model, server_options);
  if (!servers) return servers.error();
  note("restarted for the task: robot server " + (*servers)->robot_address() + ", vision server " +
       (*servers)->vision_address());

  step(3, "connecting the session and taking the lease");
  session::SessionOptions session_options;
  std::unique_ptr<record::ServerRecorder> mcap;
  if (!options.record_path.empty()) {
    record::ServerRecorderOptions recording;
    recording.robot_address = (*servers)->robot_address();
    recording.vision_address = (*servers)->vision_address();
    recording.token = (*servers)->token();
    recording.client_name = "telear-demo-record";
    recording.recorder.path = options.record_path;
    recording.recorder.metadata["recorded_by"] = "telear demo";
    recording.recorder.metadata["telear_version"] = std::string(core::version_string());
    recording.recorder.metadata["calibration_file"] = stereo_file;
    recording.recorder.metadata["robot_spec"] = options.robot;  // replay loads it
    recording.recorder.metadata["robot_tip"] = options.tip;
    // What the view draws: the session's stream, the view's ghost, the registered cameras.
    recording.stream_video = false;
    recording.stream_state = false;
    recording.recorder.ghost_from_state_stream = false;
    recording.cameras = registration->cameras;
    auto started = record::ServerRecorder::start(recording);
    if (!started) return started.error();
    mcap = std::move(started).value();
    note("recording the task to " + options.record_path);
    session::record_session_streams(session_options, *mcap);
  }
  session_options.robot.address = (*servers)->robot_address();
  session_options.robot.token = (*servers)->token();
  session_options.robot.client_name = "telear-demo";
  session_options.vision.client_name = "telear-demo";
  session_options.lease_heartbeat_s = 1.0;  // see session::SessionOptions::lease_heartbeat_s
  session_options.vision.address = (*servers)->vision_address();
  session_options.vision.token = (*servers)->token();
  session_options.vision.width = options.width;
  session_options.vision.height = options.height;
  // The cameras registered through the servers, at the operator's view size.
  vision::StereoCameraModel cameras;
  cameras.left = vision::resized_camera(registration->cameras.left, options.width, options.height);
  cameras.right =
      vision::resized_camera(registration->cameras.right, options.width, options.height);
  session_options.cameras = cameras;
  // The marker from the robot's marker file, the box from the operator's workspace file (the
  // same scene the simulated rig renders).
  session_options.marker = session::GripperMarker{marker->id, marker->corners_flange()};
  const core::WorkspaceObject* graspable = workspace->first_graspable();
  if (!graspable) return Error{"the workspace " + workspace->source + " has nothing to pick"};
  const Eigen::Vector3d box = graspable->T_base_object.translation();
  const double table_z = workspace->support_height(box.head<2>(), box.z());
  // The session checks every plan against this scene (the box carried included), and
  // run_demo_task first rehearses into the table (docs/demo.md, "Collision check").
  session_options.description = robot->description;
  session_options.workspace = *workspace;
  auto session_or = session::Session::create(model, session_options);
  if (!session_or) return session_or.error();
  session::Session& session = **session_or;
  session.connect();

  auto context = render::create_headless_context();
  if (!context) return Error{"no OpenGL context: " + context.error().message};
  std::vector<render::SceneObject> objects = {render::make_floor(3.0f, 12)};
  for (render::SceneObject& o : render::workspace_scene_objects(*workspace)) {
    objects.push_back(std::move(o));
  }
  auto view = render::ArView::create(*model, arm_body, cameras, objects);
  if (!view) return view.error();
  RecorderOptions recorder_options{options.out_dir, options.fps, options.video, {}};
  if (mcap) {
    recorder_options.on_view = [raw = mcap.get(), last = std::uint64_t{0}](
                                   const session::SessionView& v, std::int64_t ns) mutable {
      session::record_session_view(*raw, v, last, ns);
    };
  }
  SessionRecorder recorder(session, *view, recorder_options);
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
  task.true_q = [robot = &(*servers)->driver().robot()] { return robot->state().q; };
  task.table_surface_z_m = table_z;
  auto outcome = run_demo_task(session, recorder, task, progress);
  if (!outcome) return outcome.error();

  step(7, "writing the report");
  DemoFacts facts;
  if (mcap) {
    auto counts = mcap->stop();
    if (!counts) return Error{"the recording: " + counts.error().message};
    const auto report_start = std::chrono::steady_clock::now();
    nlohmann::json recorded = {{"path", options.record_path}, {"bytes", counts->bytes}};
    for (const auto& [topic, n] : counts->written) recorded["messages"][topic] = n;
    std::uint64_t dropped = 0;
    for (const auto& [topic, n] : counts->dropped) dropped += n;
    recorded["dropped"] = dropped;
    // Where each key frame is in the recording (s from its start, `telear replay --at`): the
    // view's ghost was recorded at the very time the key frame's view was drawn.
    if (auto reader = record::McapReader::open(options.record_path)) {
      const auto start = static_cast<std::int64_t>(reader->statistics().message_start_time);
      const Recording& r = recorder.recording();
      for (std::size_t i = 0; i < r.key_frames.size() && i < r.key_frame_view_ns.size(); ++i) {
        recorded["key_frames"].push_back(
            {{"file", std::filesystem::path(r.key_frames[i]).filename().string()},
             {"t_s", static_cast<double>(mcap->wall_ns(r.key_frame_view_ns[i]) - start) * 1e-9},
             {"predicted", i < r.key_frame_predicted.size() && r.key_frame_predicted[i]},
             {"states_held_back",
              i < r.key_frame_states_held_back.size() && r.key_frame_states_held_back[i]}});
      }
    }
    facts.mcap_json = recorded.dump();
    note("recorded " + options.record_path + " (" + std::to_string(counts->bytes) + " bytes)");
    // `telear report` on the recording, into the same folder: its plots and summary, which
    // report.md links. Not drawn (no gnuplot) or not read, the demo still reports and says why.
    report::ReportOptions plots;
    plots.out_dir = options.out_dir;
    plots.markdown_name = "recording_report.md";
    plots.require_plots = false;
    auto drawn = report::write_recording_report(options.record_path, plots);
    if (drawn) {
      facts.recording_report_md = plots.markdown_name;
      for (const report::PlotFile& p : drawn->plots) facts.plots.push_back({p.name, p.title});
      facts.plot_error = drawn->plot_error;
    } else {
      facts.plot_error = drawn.error().message;
    }
    note(facts.plots.empty()
             ? "warning: the recording's plots not drawn: " + facts.plot_error
             : std::to_string(facts.plots.size()) + " plots of the recording and " +
                   plots.markdown_name + " written (" +
                   core::format_fixed(core::seconds_since(report_start), 1) + " s)");
  }
  facts.robot = robot->description.name;
  facts.dof = model->dof();
  facts.tip_link = robot->description.tip_link;
  facts.calibration_json = registration->eval_json;
  facts.registration_json = registration->json;
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
  if (const session::ExecutionMonitor* monitor = session.monitor()) {
    facts.tracking = monitor->status();
    facts.tolerance_rad = monitor->options().tolerance;
  }
  facts.plan_duration_s = outcome->plan_duration_s;
  facts.waypoints = outcome->waypoints;
  facts.first_rehearsal_check = outcome->first_rehearsal_check;
  facts.final_plan_check = outcome->final_plan_check;
  facts.ar_to_vr = session.display().ar_to_vr_switches();
  facts.vr_to_ar = session.display().vr_to_ar_switches();
  facts.predicted_late_s = session.display().predicted_late_s();
  facts.switches = session.display().switches();
  facts.injected_delay_ms = options.delay_ms;
  facts.prediction = outcome->prediction;
  facts.seconds = core::seconds_since(demo_start);
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
  result.seconds = core::seconds_since(demo_start);
  return result;
}

}  // namespace telear::lab
