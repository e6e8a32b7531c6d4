#include "apps/demo_command.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <sstream>
#include <thread>

#include "apps/calibrate_command.hpp"
#include "apps/eval_command.hpp"
#include "apps/register_command.hpp"
#include "apps/sim_command.hpp"
#include "apps/sim_observations_command.hpp"
#include "telear/core/arm_body.hpp"
#include "telear/core/clock.hpp"
#include "telear/core/inverse_kinematics.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/marker_mount.hpp"
#include "telear/core/robot_loader.hpp"
#include "telear/core/workspace.hpp"
#include "telear/net/command_bytes.hpp"
#include "telear/net/latency_summary.hpp"
#include "telear/render/ar_view.hpp"
#include "telear/render/egl_context.hpp"
#include "telear/render/image_io.hpp"
#include "telear/session/embedded_servers.hpp"
#include "telear/session/session.hpp"
#include "telear/session/view_input.hpp"
#include "telear/vision/camera_file.hpp"

namespace telear::cli {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct Failure {
  std::string message;
};

constexpr int kSteps = 7;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::pair<int, int> parse_resolution(const std::string& text) {
  int w = 0, h = 0;
  char x = 0;
  std::istringstream in(text);
  if (!(in >> w >> x >> h) || x != 'x' || !in.eof() || w < 64 || h < 48 || w > 1920 || h > 1080) {
    throw Failure{"--resolution '" + text + "' must be WIDTHxHEIGHT within 64x48 .. 1920x1080"};
  }
  return {w, h};
}

// [SECTION] calibration and registration (cached)

struct Calibration {
  std::string registered_file;  // stereo camera file with T_cam_base (register's output)
  nlohmann::json eval;          // `telear eval` against the simulator's truth
  bool cached = false;
  double seconds = 0.0;
};

Calibration calibrate_and_register(const DemoOptions& options, const std::string& cache,
                                   const std::string& rig, std::ostream& log) {
  const auto start = Clock::now();
  Calibration result;
  result.registered_file = cache + "/registered.yaml";
  const std::string eval_file = cache + "/eval.json";
  const std::string key_file = cache + "/key.txt";
  std::ostringstream key;
  key << "telear demo calibration v1\nrig " << rig << "\nseed " << options.seed << "\n";
  const bool cached = fs::exists(result.registered_file) && fs::exists(eval_file) && [&] {
    std::ifstream in(key_file);
    std::stringstream s;
    s << in.rdbuf();
    return s.str() == key.str();
  }();
  if (!cached) {
    fs::create_directories(cache);
    std::ostringstream tool_out, tool_err;
    auto check = [&](int code, const char* what) {
      if (code != 0) throw Failure{std::string(what) + " failed: " + tool_err.str()};
    };
    SimCaptureOptions capture;
    capture.rig = rig;
    capture.views = 20;
    capture.seed = options.seed;
    capture.output = cache + "/capture";
    check(run_sim_capture(capture, tool_out, tool_err), "sim capture");
    CalibrateOptions calibrate;
    calibrate.left = cache + "/capture/left*.png";
    calibrate.right = cache + "/capture/right*.png";
    calibrate.pattern = "chessboard:9x6:0.03";
    calibrate.output = cache + "/stereo.yaml";
    calibrate.report = cache + "/calibration_report.json";
    check(run_calibrate(calibrate, tool_out, tool_err), "calibrate");
    SimObservationsOptions observations;
    observations.rig = rig;
    observations.configs = 20;
    observations.seed = options.seed;
    observations.output = cache + "/observations.yaml";
    check(run_sim_observations(observations, tool_out, tool_err), "sim observations");
    RegisterOptions registration;
    registration.rig = calibrate.output;
    registration.observations = observations.output;
    registration.output = result.registered_file;
    check(run_register(registration, tool_out, tool_err), "register");
    EvalOptions eval;
    eval.truth = cache + "/capture/truth.yaml";
    eval.estimate = result.registered_file;
    eval.json = eval_file;
    check(run_eval(eval, tool_out, tool_err), "eval");
    std::ofstream(key_file) << key.str();
    log << tool_out.str();
  }
  std::ifstream in(eval_file);
  result.eval = nlohmann::json::parse(in, nullptr, false);
  if (result.eval.is_discarded()) throw Failure{"cannot read " + eval_file};
  result.cached = cached;
  result.seconds = seconds_since(start);
  return result;
}

// [SECTION] the pick-and-place task

// The grasp: the gripper's centre (between the fingers) at the box's centre, its fingers
// pointing down, tilted as little as the arm's limits allow, and spun about its own axis so
// that its marker side (+x6) faces the cameras as squarely as possible (so the live
// registration check sees the marker). Candidates R = Rz(heading) Ry(tilt) R_down Rz(spin)
// are scored by tilt + the marker's angle away from the cameras; the best one whose every
// task position has an IK solution within the limits wins. Returns the rotation of the
// gripper's link (link 6) in the base frame and a note for the terminal.
std::pair<Eigen::Matrix3d, std::string> grasp_orientation(
    const core::RobotModel& model, const Eigen::Vector3d& grip_link,
    const std::vector<Eigen::Vector3d>& grip_positions, const Eigen::VectorXd& q_start,
    const Eigen::Vector3d& camera_base) {
  const Eigen::Vector3d to_camera = (camera_base - grip_positions.front()).normalized();
  Eigen::Matrix3d down;
  down.col(0) = Eigen::Vector3d::UnitX();
  down.col(1) = -Eigen::Vector3d::UnitY();
  down.col(2) = -Eigen::Vector3d::UnitZ();
  const auto rad = [](int deg) { return deg * M_PI / 180.0; };
  struct Candidate {
    double score;
    int tilt, away;
    Eigen::Matrix3d R;
  };
  std::vector<Candidate> candidates;
  for (int tilt = 0; tilt <= 60; tilt += 10) {
    for (int heading = 0; heading < 360; heading += (tilt == 0 ? 360 : 30)) {
      for (int spin = 0; spin < 360; spin += 30) {
        const Eigen::Matrix3d R =
            (Eigen::AngleAxisd(rad(heading), Eigen::Vector3d::UnitZ()) *
             Eigen::AngleAxisd(rad(tilt), Eigen::Vector3d::UnitY()))
                .toRotationMatrix() *
            down * Eigen::AngleAxisd(rad(spin), Eigen::Vector3d::UnitZ()).toRotationMatrix();
        const double away = std::acos(std::clamp(R.col(0).dot(to_camera), -1.0, 1.0)) * 180 / M_PI;
        candidates.push_back({tilt + away, tilt, static_cast<int>(std::lround(away)), R});
      }
    }
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& a, const Candidate& b) { return a.score < b.score; });
  for (const Candidate& c : candidates) {
    Eigen::VectorXd q = q_start;
    bool ok = true;
    for (const Eigen::Vector3d& p : grip_positions) {
      Eigen::Isometry3d T_base_link = Eigen::Isometry3d::Identity();
      T_base_link.linear() = c.R;
      T_base_link.translation() = p - c.R * grip_link;
      auto solution = core::solve_ik_nearest(model, T_base_link * model.T_flange_tool(), q);
      if (!solution) {
        ok = false;
        break;
      }
      q = solution->q;
    }
    if (ok) {
      std::ostringstream note;
      note << "gripper tilted " << c.tilt << " deg, its marker " << c.away
           << " deg away from facing the cameras";
      return {c.R, note.str()};
    }
  }
  throw Failure{"no gripper orientation reaches the box within the joint limits"};
}

struct TaskStep {
  std::string label;
  Eigen::Vector3d grip_position;
  std::optional<double> gripper;  // on arrival
  double dwell = 0.0;             // s at the pose after arrival (a repeated waypoint)
};

std::vector<TaskStep> pick_and_place_steps(const Eigen::Vector3d& box,
                                           const Eigen::Vector3d& place) {
  const Eigen::Vector3d up(0, 0, 0.12);
  return {
      {"approach", box + up, 1.0, 0.0},
      {"grasp", box, 0.0, 1.2},
      {"lift", box + up, std::nullopt, 0.0},
      {"carry", place + up, std::nullopt, 0.0},
      {"place", place, 1.0, 1.2},
      {"retreat", place + up, std::nullopt, 0.0},
  };
}

// [SECTION] recording

struct LatencySeries {
  std::vector<double> capture_to_encode, encode, send_queue, network, decode, total;
  void add(const net::StageLatency& l) {
    capture_to_encode.push_back(l.capture_to_encode_s);
    encode.push_back(l.encode_s);
    send_queue.push_back(l.send_queue_s);
    network.push_back(l.network_s);
    decode.push_back(l.decode_s);
    total.push_back(l.total_s);
  }
};

using net::percentile;

nlohmann::json latency_json(const std::vector<double>& v) {
  return {{"p50_ms", percentile(v, 50) * 1e3},
          {"p99_ms", percentile(v, 99) * 1e3},
          {"samples", v.size()}};
}

struct ResidualSeries {
  std::vector<double> rms[2];
  std::vector<double> max[2];
};

class Recorder {
 public:
  Recorder(session::Session& session, render::ArView& view, const DemoOptions& options,
           const std::string& out_dir)
      : session_(session), view_(view), options_(options), out_dir_(out_dir) {}

  Status open_video(int width, int height) {
    if (options_.no_video) return Status::Ok();
    video_path_ = out_dir_ + "/demo_stereo.mp4";
    writer_.open(video_path_, cv::VideoWriter::fourcc('m', 'p', '4', 'v'), options_.fps,
                 cv::Size(width, height));
    if (!writer_.isOpened()) return Error{"cannot write the video " + video_path_};
    return Status::Ok();
  }

  // One display frame: session update, AR view, video frame; paced at options.fps.
  void tick() {
    const double period = 1.0 / options_.fps;
    const auto now = Clock::now();
    const double dt = last_ ? std::chrono::duration<double>(now - *last_).count() : period;
    last_ = now;
    session_.update(dt);
    const session::SessionView& v = session_.view();
    if (v.frame && v.frame->frame_id != last_frame_id_) {
      last_frame_id_ = v.frame->frame_id;
      latency_.add(v.frame->latency);
      ++frames_shown_;
    }
    const session::SessionStats stats = session_.stats();
    if (stats.residual_checks != residual_checks_) {
      residual_checks_ = stats.residual_checks;
      const session::EyeResidual* eyes[2] = {&stats.residual.left, &stats.residual.right};
      for (int i = 0; i < 2; ++i) {
        if (eyes[i]->valid()) {
          residuals_.rms[i].push_back(eyes[i]->rms_px);
          residuals_.max[i].push_back(eyes[i]->max_px);
        } else {
          ++residual_misses_[i];
          residual_message_[i] = eyes[i]->message;
        }
      }
    }
    view_.render(session::ar_view_input(v));
    last_image_ = view_.read_composed_rgb();
    if (writer_.isOpened()) {
      cv::Mat rgb(last_image_.height, last_image_.width, CV_8UC3, last_image_.pixels.data());
      cv::Mat bgr;
      cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
      writer_.write(bgr);
      ++video_frames_;
    }
    ++ticks_;
    const double spent = std::chrono::duration<double>(Clock::now() - now).count();
    if (spent < period) std::this_thread::sleep_for(std::chrono::duration<double>(period - spent));
  }

  std::string key_frame(const std::string& name) {
    const std::string path = out_dir_ + "/" + name + ".png";
    if (Status s = render::write_png(path, last_image_); !s.ok()) throw Failure{s.error().message};
    key_frames_.push_back(path);
    return path;
  }

  void close() { writer_.release(); }

  const LatencySeries& latency() const { return latency_; }
  const ResidualSeries& residuals() const { return residuals_; }
  int residual_misses(int eye) const { return residual_misses_[eye]; }
  const std::string& residual_message(int eye) const { return residual_message_[eye]; }
  int ticks() const { return ticks_; }
  int frames_shown() const { return frames_shown_; }
  int video_frames() const { return video_frames_; }
  const std::string& video_path() const { return video_path_; }
  const std::vector<std::string>& key_frames() const { return key_frames_; }

 private:
  session::Session& session_;
  render::ArView& view_;
  const DemoOptions& options_;
  std::string out_dir_;
  cv::VideoWriter writer_;
  std::string video_path_;
  std::optional<Clock::time_point> last_;
  std::uint64_t last_frame_id_ = 0;
  LatencySeries latency_;
  ResidualSeries residuals_;
  int residual_checks_ = 0;
  int residual_misses_[2] = {0, 0};
  std::string residual_message_[2];
  int ticks_ = 0, frames_shown_ = 0, video_frames_ = 0;
  core::Image last_image_;
  std::vector<std::string> key_frames_;
};

double mean(const std::vector<double>& v) {
  if (v.empty()) return 0.0;
  double s = 0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}

double max_of(const std::vector<double>& v) {
  return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end());
}

std::string fixed(double v, int digits) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}

}  // namespace

int run_demo(const DemoOptions& options, std::ostream& out, std::ostream& err) {
  const auto demo_start = Clock::now();
  try {
    // [SECTION] set-up
    const auto [width, height] = parse_resolution(options.resolution);
    if (options.delay_ms < 0 || options.delay_ms > 5000) {
      throw Failure{"--delay-ms " + std::to_string(options.delay_ms) + " is outside 0..5000"};
    }
    if (!(options.fps >= 1 && options.fps <= 60)) throw Failure{"--fps must be in 1..60"};
    fs::create_directories(options.out);
    const std::string cache = options.cache.empty() ? options.out + "/cache" : options.cache;
    const std::string rig = core::data_directory() + "/rigs/puma560_rig.yaml";
    auto step = [&](int n, const std::string& what) {
      out << "[" << n << "/" << kSteps << "] " << what << " ("
          << fixed(seconds_since(demo_start), 1) << " s)" << std::endl;
    };

    step(1, "calibrating the simulated stereo rig and registering the robot");
    std::ostringstream tool_log;
    const Calibration calibration = calibrate_and_register(options, cache, rig, tool_log);
    out << "      " << (calibration.cached ? "cached in " : "written to ") << cache << " ("
        << fixed(calibration.seconds, 1) << " s)\n";
    auto camera_file = vision::load_camera_file(calibration.registered_file);
    if (!camera_file || !camera_file->right) {
      throw Failure{"cannot load the registered calibration: " +
                    (camera_file ? std::string("not a stereo file") : camera_file.error().message)};
    }
    auto model_or = core::load_robot("puma560");
    if (!model_or) throw Failure{model_or.error().message};
    const core::RobotModelPtr model = *model_or;

    step(2, "starting the simulated robot server and vision server on loopback");
    session::EmbeddedServersOptions server_options;
    server_options.calibration_file = calibration.registered_file;
    server_options.seed = options.seed;
    server_options.fps = options.camera_fps;
    // A ready pose away from the wrist singularity of qr (q5 = 0).
    server_options.initial_q =
        (Eigen::VectorXd(6) << 0.0, 30.0, -120.0, 0.0, -45.0, 0.0).finished() * (M_PI / 180.0);
    auto servers = session::EmbeddedServers::create(model, server_options);
    if (!servers) throw Failure{servers.error().message};
    out << "      robot server " << (*servers)->robot_address() << ", vision server "
        << (*servers)->vision_address() << "\n";

    step(3, "connecting the session and taking the lease");
    session::SessionOptions session_options;
    session_options.robot.address = (*servers)->robot_address();
    session_options.robot.token = (*servers)->token();
    session_options.robot.client_name = "telear-demo";
    session_options.lease_heartbeat_s = 1.0;  // see SessionOptions::lease_heartbeat_s
    session_options.vision.address = (*servers)->vision_address();
    session_options.vision.width = width;
    session_options.vision.height = height;
    vision::StereoCameraModel cameras;
    cameras.left = vision::resized_camera(camera_file->left, width, height);
    cameras.right = vision::resized_camera(*camera_file->right, width, height);
    session_options.cameras = cameras;
    auto marker = core::marker_mount_for(*model);
    if (!marker) throw Failure{marker.error().message};
    session_options.marker = session::GripperMarker{marker->id, marker->corners_flange()};
    auto session_or = session::Session::create(model, session_options);
    if (!session_or) throw Failure{session_or.error().message};
    session::Session& session = **session_or;
    session.connect();

    auto context = render::create_headless_context();
    if (!context) throw Failure{"no OpenGL context: " + context.error().message};
    auto body = core::body_description_for(*model);
    if (!body) throw Failure{body.error().message};
    const core::ArmBody arm_body = core::build_arm_body(*body);
    auto workspace = core::load_workspace_file(core::default_workspace_file(model->name()));
    if (!workspace) throw Failure{workspace.error().message};
    const core::WorkspaceObject* graspable = workspace->first_graspable();
    if (!graspable) throw Failure{"the workspace " + workspace->source + " has nothing to pick"};
    const Eigen::Vector3d box = graspable->T_base_object.translation();
    std::vector<render::SceneObject> objects = {render::make_floor(3.0f, 12)};
    for (render::SceneObject& o : render::workspace_scene_objects(*workspace)) {
      objects.push_back(std::move(o));
    }
    auto view = render::ArView::create(*model, arm_body, cameras, objects);
    if (!view) throw Failure{view.error().message};
    Recorder recorder(session, *view, options, options.out);
    const render::ComposedSize size =
        render::composed_size(render::StereoLayout::kSideBySide, width, height);
    if (Status s = recorder.open_video(size.width, size.height); !s.ok())
      throw Failure{s.error().message};

    const auto wait_start = Clock::now();
    while (!(session.view().real && session.view().frame)) {
      if (seconds_since(wait_start) > 30) {
        throw Failure{"no robot state or video from the embedded servers after 30 s"};
      }
      session.update(0.02);
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    if (Status s = session.take_control(); !s.ok()) throw Failure{s.error().message};
    for (int i = 0; i < static_cast<int>(options.fps); ++i) recorder.tick();
    recorder.key_frame("keyframe_1_start");

    // [SECTION] rehearsal
    step(4, "rehearsing the pick-and-place on the ghost");
    if (Status s = session.ghost_to_real(); !s.ok()) throw Failure{s.error().message};
    const Eigen::Vector3d place = box + Eigen::Vector3d(0.0, -0.2, 0.0);
    const auto steps = pick_and_place_steps(box, place);
    const Eigen::Vector3d grip_link = arm_body.gripper
                                          ? Eigen::Vector3d(arm_body.gripper->centre.cast<double>())
                                          : Eigen::Vector3d::Zero();
    std::vector<Eigen::Vector3d> positions;
    for (const auto& s : steps) positions.push_back(s.grip_position);
    const Eigen::Vector3d camera_base = cameras.left.T_cam_base.inverse().translation();
    const auto [R, grasp_note] =
        grasp_orientation(*model, grip_link, positions, session.ghost().q(), camera_base);
    out << "      grasp: " << grasp_note << "\n";
    (void)session.plan().set_scales(0.5, 0.5);
    if (Status s = session.add_ghost_waypoint(0.0, "start"); !s.ok())
      throw Failure{s.error().message};
    for (const TaskStep& task : steps) {
      Eigen::Isometry3d T_base_link = Eigen::Isometry3d::Identity();
      T_base_link.linear() = R;
      T_base_link.translation() = task.grip_position - R * grip_link;
      const core::MotionOutcome outcome =
          session.move_ghost(core::CartesianTarget{T_base_link * model->T_flange_tool()});
      if (!outcome.accepted) {
        throw Failure{"rehearsal: " + task.label + ": " + outcome.rejection.message};
      }
      if (task.gripper) (void)session.ghost().set_gripper(*task.gripper);
      if (Status s = session.add_ghost_waypoint(0.0, task.label); !s.ok()) {
        throw Failure{s.error().message};
      }
      if (task.dwell > 0) (void)session.add_ghost_waypoint(task.dwell, task.label + " (dwell)");
      for (int i = 0; i < static_cast<int>(options.fps / 3); ++i) recorder.tick();
      if (task.label == "grasp") recorder.key_frame("keyframe_2_rehearsal_grasp");
    }
    auto trajectory = session.plan().trajectory();
    if (!trajectory) throw Failure{trajectory.error().message};
    out << "      " << session.plan().size() << " waypoints, " << fixed(trajectory->duration(), 2)
        << " s\n";

    // [SECTION] preview
    step(5, "previewing the plan on the ghost over the live video");
    if (Status s = session.start_preview({.loop = false, .speed = 2.0}); !s.ok()) {
      throw Failure{s.error().message};
    }
    bool preview_key = false;
    while (session.preview() && !session.preview()->current().at_end) {
      recorder.tick();
      if (!preview_key && session.preview()->time() > 0.45 * trajectory->duration()) {
        recorder.key_frame("keyframe_3_preview");
        preview_key = true;
      }
    }
    session.stop_preview();
    (void)session.ghost_to_real();

    // [SECTION] execution
    step(6, "validating, executing on the robot and monitoring");
    const session::ValidationReport validation = session.validate_plan();
    out << "      validation: " << validation.summary() << "\n";
    if (!validation.ok()) throw Failure{"the plan is not valid: " + validation.summary()};
    const std::uint64_t bytes_before = session.robot().command_bytes_sent();
    auto ack = session.execute_plan();
    if (!ack) throw Failure{ack.error().message};
    const std::uint64_t plan_bytes = session.robot().command_bytes_sent() - bytes_before;
    const auto exec_start = Clock::now();
    const double duration = trajectory->duration();
    const double delay_s = options.delay_ms / 1000.0;
    bool grasp_key = false, vr_key = false;
    while (session.executing()) {
      const double t = seconds_since(exec_start);
      if (t > duration + 30) throw Failure{"the execution did not finish in time"};
      const bool in_window = t > 0.4 * duration && t < 0.4 * duration + 3.0;
      session.set_injected_video_delay(in_window ? delay_s : 0.0);
      recorder.tick();
      if (!grasp_key && t > 0.3 * duration) {
        recorder.key_frame("keyframe_4_execution");
        grasp_key = true;
      }
      if (!vr_key && session.view().display.mode == session::DisplayMode::kVR) {
        recorder.key_frame("keyframe_5_vr_while_video_late");
        vr_key = true;
      }
    }
    session.set_injected_video_delay(0.0);
    for (int i = 0; i < static_cast<int>(options.fps * 1.5); ++i) recorder.tick();
    recorder.key_frame("keyframe_6_done");
    recorder.close();
    const std::string result = session.last_execution_result();
    out << "      execution: " << result << "\n";

    // [SECTION] report
    step(7, "writing the report");
    const session::SessionStats stats = session.stats();
    const session::ExecutionMonitor* monitor = session.monitor();
    auto samples = trajectory->sampled(100.0);
    const net::CommandBytes bytes =
        net::compare_command_bytes(*samples, 100.0, std::string(32, '0'), "plan-0000000000-1");
    nlohmann::json report;
    report["calibration"] = calibration.eval;
    report["calibration_cached"] = calibration.cached;
    nlohmann::json overlay;
    const char* eye_names[2] = {"left", "right"};
    for (int i = 0; i < 2; ++i) {
      overlay[eye_names[i]] = {{"rms_px_mean", mean(recorder.residuals().rms[i])},
                               {"max_px", max_of(recorder.residuals().max[i])},
                               {"checks", recorder.residuals().rms[i].size()},
                               {"marker_not_found", recorder.residual_misses(i)},
                               {"last_miss", recorder.residual_message(i)}};
    }
    report["overlay_error_live"] = overlay;
    const LatencySeries& lat = recorder.latency();
    report["video"] = {{"resolution", options.resolution},
                       {"camera_fps", options.camera_fps},
                       {"frames_shown", recorder.frames_shown()},
                       {"display_ticks", recorder.ticks()},
                       {"fps_shown", recorder.frames_shown() / seconds_since(demo_start)},
                       {"latency",
                        {{"capture_to_encode", latency_json(lat.capture_to_encode)},
                         {"encode", latency_json(lat.encode)},
                         {"send_queue", latency_json(lat.send_queue)},
                         {"network", latency_json(lat.network)},
                         {"decode", latency_json(lat.decode)},
                         {"capture_to_decoded", latency_json(lat.total)}}},
                       {"bytes_per_s", stats.video_bytes_per_s}};
    report["bytes"] = {
        {"plan_then_send_measured", plan_bytes},
        {"plan_then_send", bytes.plan_bytes},
        {"jog_100hz", bytes.jog_stream_bytes},
        {"jog_messages", bytes.jog_messages},
        {"ratio", bytes.plan_bytes > 0 ? static_cast<double>(bytes.jog_stream_bytes) /
                                             static_cast<double>(bytes.plan_bytes)
                                       : 0.0}};
    nlohmann::json tracking;
    tracking["result"] = result;
    if (monitor) {
      const session::TrackingStatus& status = monitor->status();
      tracking["max_error_rad"] = status.max_error_so_far;
      tracking["max_error_joint"] = status.max_error_joint + 1;
      tracking["rms_error_rad"] = status.rms_error;
      tracking["samples"] = status.samples;
      tracking["tolerance_rad"] = monitor->options().tolerance;
    }
    tracking["plan_duration_s"] = duration;
    tracking["waypoints"] = session.plan().size();
    report["execution"] = tracking;
    nlohmann::json switches = nlohmann::json::array();
    for (const auto& s : session.display().switches()) {
      switches.push_back({{"from", session::to_string(s.from)},
                          {"to", session::to_string(s.to)},
                          {"reason", s.reason}});
    }
    report["display"] = {{"ar_to_vr", session.display().ar_to_vr_switches()},
                         {"vr_to_ar", session.display().vr_to_ar_switches()},
                         {"injected_delay_ms", options.delay_ms},
                         {"switches", switches}};
    report["outputs"] = {{"video", recorder.video_path()},
                         {"video_frames", recorder.video_frames()},
                         {"key_frames", recorder.key_frames()}};
    report["seconds"] = seconds_since(demo_start);
    std::ofstream(options.out + "/report.json") << report.dump(2) << "\n";

    std::ofstream md(options.out + "/report.md");
    md << "# telear demo report\n\n"
       << "Pick-and-place rehearsed on the ghost over the simulated stereo video, previewed, "
          "executed on the simulated robot as one trajectory and monitored.\n\n"
       << "| | left | right |\n|---|---|---|\n";
    if (calibration.eval.contains("left")) {
      for (const char* key : {"fx_error_percent", "cx_error_px", "cy_error_px", "registration_mm",
                              "registration_deg", "overlay_rms_px"}) {
        md << "| calibration " << key << " | " << fixed(calibration.eval["left"].value(key, 0.0), 3)
           << " | " << fixed(calibration.eval["right"].value(key, 0.0), 3) << " |\n";
      }
    }
    md << "| live overlay error (marker), mean RMS px | "
       << fixed(mean(recorder.residuals().rms[0]), 3) << " | "
       << fixed(mean(recorder.residuals().rms[1]), 3) << " |\n\n";
    md << "| stage | p50 ms | p99 ms |\n|---|---|---|\n";
    const std::pair<const char*, const std::vector<double>*> stages[] = {
        {"capture -> encode", &lat.capture_to_encode},
        {"encode", &lat.encode},
        {"send queue", &lat.send_queue},
        {"network", &lat.network},
        {"decode", &lat.decode},
        {"capture -> decoded", &lat.total}};
    for (const auto& [name, series] : stages) {
      md << "| " << name << " | " << fixed(percentile(*series, 50) * 1e3, 2) << " | "
         << fixed(percentile(*series, 99) * 1e3, 2) << " |\n";
    }
    md << "\n- video: " << options.resolution << " stereo, " << recorder.frames_shown()
       << " frames shown\n"
       << "- bytes to command the motion: plan-then-send " << bytes.plan_bytes
       << " B (one message), "
       << "jogging at 100 Hz " << bytes.jog_stream_bytes << " B (" << bytes.jog_messages
       << " messages), " << fixed(report["bytes"]["ratio"].get<double>(), 1) << "x\n"
       << "- execution: " << result;
    if (monitor) {
      md << ", max tracking error " << fixed(monitor->status().max_error_so_far * 1e3, 3)
         << " mrad (tolerance " << fixed(monitor->options().tolerance * 1e3, 0) << " mrad)";
    }
    md << "\n- display: " << session.display().ar_to_vr_switches() << " AR -> VR and "
       << session.display().vr_to_ar_switches() << " VR -> AR switches (injected delay "
       << options.delay_ms << " ms)\n"
       << "- total " << fixed(seconds_since(demo_start), 1) << " s\n";
    md.close();

    session.disconnect();
    (*servers)->stop();
    out << "telear demo: wrote " << options.out << "/report.md, report.json, "
        << recorder.key_frames().size() << " key frames"
        << (recorder.video_path().empty() ? "" : ", " + recorder.video_path()) << " in "
        << fixed(seconds_since(demo_start), 1) << " s\n";
    return result == "completed" ? 0 : 1;
  } catch (const Failure& f) {
    err << "telear demo: " << f.message << "\n";
    return 2;
  }
}

}  // namespace telear::cli
