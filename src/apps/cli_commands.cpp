// The command line's tool families (apps/cli_app.hpp): each registration adds its options
// and the handler that runs the subcommand's library call. The servers' families are in
// main.cpp, the console, the benchmarks and the usage conventions in cli_conventions.cpp.

#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <string>

#include "apps/calibrate_command.hpp"
#include "apps/capture_command.hpp"
#include "apps/cli_app.hpp"
#include "apps/demo_command.hpp"
#include "apps/eval_command.hpp"
#include "apps/kin_command.hpp"
#include "apps/plan_command.hpp"
#include "apps/record_command.hpp"
#include "apps/register_command.hpp"
#include "apps/render_command.hpp"
#include "apps/report_command.hpp"
#include "apps/robot_acm_command.hpp"
#include "apps/sim_command.hpp"
#include "apps/sim_frame_command.hpp"
#include "apps/sim_observations_command.hpp"

namespace telear::cli {
// [SECTION] demo (the README's main command; docs/demo.md)

void add_demo_command(CLI::App& app, Commands& commands) {
  auto options = std::make_shared<DemoOptions>();
  DemoOptions& demo = *options;
  CLI::App* demo_app = app.add_subcommand(
      "demo", "the whole workflow on the simulated robot and rig: rehearse, preview, execute");
  add_robot_arguments(demo_app, demo, true);  // an arm with a rig: puma560, ur6, arm7
  demo_app->add_option("--out", demo.out, "output folder (video, key frames, report)")
      ->capture_default_str();
  demo_app->add_option("--cache", demo.cache, "calibration cache folder (default OUT/cache)");
  demo_app->add_option("--resolution", demo.resolution, "stereo video size WIDTHxHEIGHT per eye")
      ->capture_default_str()
      ->check(image_size_validator({64, 48}, {1920, 1080}));
  demo_app
      ->add_option("--delay-ms", demo.delay_ms,
                   "video delay injected for 3 s of the execution (AR -> VR -> AR); 0: none")
      ->capture_default_str();
  demo_app->add_option("--seed", demo.seed, "calibration views and sensor noise")
      ->capture_default_str();
  demo_app->add_option("--fps", demo.fps, "display loop and recorded video rate")
      ->capture_default_str();
  demo_app->add_option("--camera-fps", demo.camera_fps, "the simulated cameras' rate")
      ->capture_default_str();
  demo_app
      ->add_option("--live-multisample", demo.live_multisample,
                   "the simulated cameras' anti-aliasing, MSAA samples per pixel, for the live "
                   "video and the registration capture (1: fastest, the marker's edges on whole "
                   "pixels)")
      ->capture_default_str();
  demo_app->add_flag("--no-video", demo.no_video, "skip the MP4 (key frames and report only)");
  CLI::Option* record = demo_app->add_option(
      "--record", demo.record,
      "record the task to this MCAP file (Foxglove; docs/recording.md); default OUT/session.mcap");
  demo_app
      ->add_flag("--no-record", demo.no_record,
                 "record nothing (the report then has no plots of the recording)")
      ->excludes(record);

  commands.push_back({demo_app, [options] { return run_demo(*options, std::cout, std::cerr); }});
}

// [SECTION] record (docs/recording.md)

void add_record_command(CLI::App& app, Commands& commands) {
  auto options = std::make_shared<RecordOptions>();
  RecordOptions& record = *options;
  CLI::App* record_app = app.add_subcommand(
      "record", "record running servers' streams to MCAP (a passive observer: no lease)");
  record_app->add_option("--robot", record.robot_server, "the robot server, HOST:PORT")->required();
  record_app->add_option("--vision", record.vision_server,
                         "the vision server, HOST:PORT (none: no video recorded)");
  record_app->add_option("--token-file", record.token_file, "file whose first line is the token");
  record_app->add_option("--tls-ca", record.tls_ca_file,
                         "the servers speak TLS: trust this CA (PEM)");
  record_app->add_option("-o,--output", record.output, "the MCAP file to write")->required();
  record_app->add_option("--seconds", record.seconds, "how long to record; 0: until Ctrl-C")
      ->capture_default_str();
  record_app->add_option("--state-rate", record.state_rate_hz, "robot states per second, 1..250")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 250.0));
  commands.push_back(
      {record_app, [options] { return run_record(*options, std::cout, std::cerr); }});
}

// [SECTION] report (docs/recording.md, "Plots: telear report")

void add_report_command(CLI::App& app, Commands& commands) {
  auto options = std::make_shared<ReportCommandOptions>();
  ReportCommandOptions& report = *options;
  CLI::App* report_app = app.add_subcommand(
      "report", "plots (PNG, gnuplot) and a Markdown summary of a recording (MCAP)");
  report_app->add_option("recording", report.input, "the MCAP file, F.mcap")->required();
  report_app->add_option("-o,--output", report.output_dir, "the folder to write into")->required();
  commands.push_back(
      {report_app, [options] { return run_report(*options, std::cout, std::cerr); }});
}

// [SECTION] kin

void add_kin_commands(CLI::App& app, Commands& commands) {
  auto options = std::make_shared<KinOptions>();
  KinOptions& kin = *options;
  CLI::App* kin_app = app.add_subcommand("kin", "the arm's geometric model: FK, IK, limits");
  kin_app->require_subcommand(1);
  auto add_robot = [&kin](CLI::App* sub) { add_robot_arguments(sub, kin, false); };
  CLI::App* kin_info = kin_app->add_subcommand("info", "joints, limits, named configurations");
  add_robot(kin_info);
  kin_info->add_flag("--json", kin.json, "print JSON");
  CLI::App* kin_fk = kin_app->add_subcommand("fk", "forward kinematics: tool pose and frames");
  add_robot(kin_fk);
  kin_fk->add_option("--q", kin.q, "joint values q1,...,qn (rad, or deg with --deg) or a name")
      ->required();
  kin_fk->add_flag("--deg", kin.degrees, "joint values in degrees");
  kin_fk->add_flag("--json", kin.json, "print JSON (row-major 4x4, metres)");
  CLI::App* kin_demo = kin_app->add_subcommand("demo", "FK at the named configurations");
  add_robot(kin_demo);
  CLI::App* kin_ik = kin_app->add_subcommand("ik", "inverse kinematics: joints for a tool pose");
  add_robot(kin_ik);
  kin_ik->add_option_function<std::string>(
      "--T", [&kin](const std::string& v) { kin.T = v; },
      "tool pose: 16 numbers, row-major 4x4 (metres), comma or blank separated");
  kin_ik->add_option_function<std::string>(
      "--pose", [&kin](const std::string& v) { kin.pose = v; },
      "tool pose x,y,z,roll,pitch,yaw (m; rad, or deg with --deg); e.g. --pose=-0.2,...");
  kin_ik->add_option("--config", kin.config, "configuration letters l/r, u/d, n/f, e.g. lun");
  kin_ik->add_flag("--deg", kin.degrees, "angles (pose and joint values) in degrees");
  kin_ik->add_flag("--json", kin.json, "print JSON");

  commands.push_back(
      {kin_info, [options] { return run_kin_info(*options, std::cout, std::cerr); }});
  commands.push_back({kin_fk, [options] { return run_kin_fk(*options, std::cout, std::cerr); }});
  commands.push_back(
      {kin_demo, [options] { return run_kin_demo(*options, std::cout, std::cerr); }});
  commands.push_back({kin_ik, [options] { return run_kin_ik(*options, std::cout, std::cerr); }});
}

// [SECTION] render

void add_render_command(CLI::App& app, Commands& commands) {
  auto options = std::make_shared<RenderOptions>();
  RenderOptions& render = *options;
  CLI::App* render_app =
      app.add_subcommand("render", "draw the arm through a camera, on a video frame, to PNG");
  add_robot_arguments(render_app, render, true);
  render_app
      ->add_option("--q", render.q, "joint values q1,...,qn (rad, or deg with --deg) or a name")
      ->required();
  render_app->add_flag("--deg", render.degrees, "joint values in degrees");
  render_app->add_option("--camera", render.camera,
                         "camera file (mono or stereo) or left.yaml,right.yaml; default: a view "
                         "of the whole arm");
  render_app->add_option("--eye", render.eye,
                         "left, right or both (default: both for a stereo camera file, else "
                         "left)");
  render_app->add_option("--stereo", render.stereo, "sbs, tb, anaglyph or separate")
      ->capture_default_str();
  render_app->add_option("--background", render.background,
                         "video frame (PNG/JPEG) behind the arm, or left.png,right.png");
  render_app->add_flag("--wireframe", render.wireframe, "wire-frame instead of solid");
  render_app->add_option("--segments", render.segments, "segments of every cylinder (3..512)");
  render_app->add_option("--gripper", render.gripper, "gripper opening, m");
  render_app->add_option("--alpha", render.alpha, "opacity of the arm (0, 1]; < 1: ghost")
      ->capture_default_str();
  render_app->add_flag("--undistort", render.undistort,
                       "undistort the frame and draw with K (default: warp the arm into the raw "
                       "frame)");
  render_app->add_flag("--floor", render.floor, "a checkered floor at z = 0");
  render_app->add_flag("--cube", render.cube, "the seed's cube in front of the arm");
  render_app->add_flag("--no-arm", render.no_arm, "leave the arm out (the scene alone)");
  render_app->add_option("--width", render.width, "image width of the default view")
      ->capture_default_str();
  render_app->add_option("--height", render.height, "image height of the default view")
      ->capture_default_str();
  render_app->add_option("-o,--output", render.output, "PNG to write")->required();

  commands.push_back(
      {render_app, [options] { return run_render(*options, std::cout, std::cerr); }});
}

// [SECTION] plan

void add_plan_commands(CLI::App& app, Commands& commands) {
  auto options = std::make_shared<PlanCheckOptions>();
  PlanCheckOptions& check = *options;
  CLI::App* plan_app = app.add_subcommand("plan", "saved plans (the session's plan YAML)");
  plan_app->require_subcommand(1);
  CLI::App* check_app = plan_app->add_subcommand(
      "check", "continuous collision check of a plan against a workspace and the arm itself");
  add_robot_arguments(check_app, check, true);
  check_app->add_option("--workspace", check.workspace,
                        "workspace file (default: the robot's shipped table scene)");
  check_app->add_option("--plan", check.plan, "plan file (YAML)")->required();
  check_app->add_flag("--json", check.json, "print JSON");
  check_app->add_flag("--exact-meshes", check.exact_meshes,
                      "check mesh links by their triangles, not their parts' convex hulls "
                      "(slower; the hulls err on the safe side: docs/collision.md)");
  commands.push_back(
      {check_app, [options] { return run_plan_check(*options, std::cout, std::cerr); }});

  auto hash_options = std::make_shared<PlanHashOptions>();
  CLI::App* hash_app = plan_app->add_subcommand(
      "hash", "the plan's SHA-256 as the plan message carries it (telear/core/plan_hash.hpp)");
  add_robot_arguments(hash_app, *hash_options, true);
  hash_app->add_option("--plan", hash_options->plan, "plan file (YAML)")->required();
  hash_app->add_flag("--json", hash_options->json, "print JSON (hash, algorithm, duration)");
  commands.push_back(
      {hash_app, [hash_options] { return run_plan_hash(*hash_options, std::cout, std::cerr); }});
}

// [SECTION] robot (docs/collision.md, "The allowed-collision matrix")

void add_robot_commands(CLI::App& app, Commands& commands) {
  auto options = std::make_shared<RobotAcmOptions>();
  CLI::App* robot_app = app.add_subcommand("robot", "robot files");
  robot_app->require_subcommand(1);
  CLI::App* acm_app = robot_app->add_subcommand(
      "acm", "the allowed-collision matrix by sampling, as the robot file's YAML block");
  add_robot_arguments(acm_app, *options, true);
  acm_app->add_option("--samples", options->samples, "random configurations")
      ->capture_default_str()
      ->check(CLI::Range(1, 10'000'000));
  acm_app->add_option("--seed", options->seed, "random seed")->capture_default_str();
  acm_app->add_flag("--never", options->never, "also allow pairs in contact in no sample");
  acm_app->add_flag("!--no-constant", options->constant,
                    "keep checking pairs whose distance is the same in every sample");
  acm_app
      ->add_option("--constant-tolerance", options->constant_tolerance_m,
                   "m: a pair whose distance varies by at most this over the samples is at a "
                   "constant distance")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 0.01));
  acm_app->add_option("-o,--output", options->output, "write the block to FILE");
  commands.push_back(
      {acm_app, [options] { return run_robot_acm(*options, std::cout, std::cerr); }});
}

// [SECTION] calibrate, register, eval

void add_calibration_commands(CLI::App& app, Commands& commands) {
  auto calibrate_options = std::make_shared<CalibrateOptions>();
  CalibrateOptions& calibrate = *calibrate_options;
  CLI::App* calibrate_app = app.add_subcommand(
      "calibrate",
      "camera calibration, mono or stereo, from images of a chessboard, circles or ChArUco");
  calibrate_app
      ->add_option("--left", calibrate.left,
                   "the (left) camera's images, a quoted glob: 'DIR/left*.png'")
      ->required();
  calibrate_app->add_option("--right", calibrate.right,
                            "the right camera's images (stereo), a quoted glob; pairs are "
                            "matched in sorted name order");
  calibrate_app
      ->add_option("--pattern", calibrate.pattern,
                   "chessboard:COLSxROWS:SQUARE_M (inner corners, e.g. chessboard:9x6:0.025) or "
                   "circles:COLSxROWS:SPACING_M (asymmetric grid) or "
                   "charuco:SXxSY:SQUARE_M:MARKER_M:DICT (squares, e.g. "
                   "charuco:7x5:0.04:0.03:4x4_50; partial views count)")
      ->required();
  calibrate_app->add_option("-o,--output", calibrate.output, "camera file (YAML) to write")
      ->required();
  calibrate_app->add_option("--report", calibrate.report, "JSON report to write");
  calibrate_app->add_option("--camera-info", calibrate.camera_info,
                            "also write ROS camera_info: PREFIX_left.yaml, PREFIX_right.yaml "
                            "(or PREFIX.yaml)");
  calibrate_app
      ->add_option("--outlier-factor", calibrate.outlier_factor,
                   "reject views whose error exceeds this x the median; 0 keeps every view")
      ->capture_default_str();
  calibrate_app
      ->add_option("--model", calibrate.model,
                   "lens model: plumb_bob (k1 k2 p1 p2 k3), rational_polynomial (k1..k6, wide "
                   "angle) or equidistant (fisheye k1..k4)")
      ->capture_default_str();
  calibrate_app->add_flag("--estimate-k3", calibrate.estimate_k3,
                          "estimate k3 too (default: held at 0, two radial terms)");
  calibrate_app->add_flag("--zero-tangential", calibrate.zero_tangential, "hold p1, p2 at 0");
  calibrate_app->add_flag("--keep-mono-intrinsics", calibrate.keep_mono_intrinsics,
                          "stereo: keep each camera's own calibration, fit only R, T");

  auto register_shared = std::make_shared<RegisterOptions>();
  RegisterOptions& register_options = *register_shared;
  CLI::App* register_app = app.add_subcommand(
      "register",
      "the robot base's pose in each camera (T_cam_base) from marker observations or captures");
  register_app->add_option("--rig", register_options.rig,
                           "stereo camera file with R, T (telear calibrate's output); with "
                           "--captures, default: the capture's own");
  add_robot_arguments(register_app, register_options, false);
  register_app->add_option("--observations", register_options.observations,
                           "observations YAML (telear sim observations)");
  register_app->add_option("--captures", register_options.captures,
                           "capture folder (telear capture): detect the marker, hand-eye");
  register_app->add_option("--target", register_options.target,
                           "with --captures: the target on the flange, e.g. "
                           "charuco:5x5:0.06:0.045:4x4_50 (default: the capture's, else the "
                           "robot's marker; docs/registration.md, Targets)");
  register_app->add_option("-o,--output", register_options.output, "camera file to write")
      ->required();
  register_app
      ->add_option("--max-iterations", register_options.max_iterations,
                   "Levenberg-Marquardt iterations at most")
      ->capture_default_str();

  auto eval_shared = std::make_shared<EvalOptions>();
  EvalOptions& eval_options = *eval_shared;
  CLI::App* eval_app = app.add_subcommand(
      "eval", "accuracy of calibration + registration against ground truth (sim)");
  eval_app->add_option("--truth", eval_options.truth, "true stereo cameras (sim truth.yaml)")
      ->required();
  eval_app->add_option("--estimate", eval_options.estimate, "registered stereo camera file")
      ->required();
  add_robot_arguments(eval_app, eval_options, true);
  eval_app->add_option("--json", eval_options.json, "also write the table as JSON to FILE");
  eval_app
      ->add_option("--configurations", eval_options.configurations,
                   "random arm configurations of the overlay error")
      ->capture_default_str();
  eval_app->add_option("--spacing", eval_options.spacing_m, "body sample spacing, m")
      ->capture_default_str();

  auto capture_shared = std::make_shared<CaptureOptions>();
  CaptureOptions& capture = *capture_shared;
  CLI::App* capture_app = app.add_subcommand(
      "capture", "move the arm through poses and record stereo frames for registration");
  capture_app->add_option("--robot", capture.robot_server, "robot server HOST:PORT")->required();
  capture_app->add_option("--vision", capture.vision_server, "vision server HOST:PORT")->required();
  capture_app->add_option("--token-file", capture.token_file, "file whose first line is the token");
  add_robot_arguments(capture_app, capture, false, "--arm");
  capture_app->add_option("--poses", capture.poses, "auto:N or a YAML file of joint vectors")
      ->capture_default_str();
  capture_app->add_option("--frames", capture.frames, "stereo frames per pose")
      ->capture_default_str();
  capture_app->add_option("--speed", capture.speed, "fraction of the joint speed limits")
      ->capture_default_str();
  capture_app->add_option("--settle", capture.settle_s, "s to wait at rest before the frames")
      ->capture_default_str();
  capture_app->add_option("--seed", capture.seed, "seed of the automatic poses")
      ->capture_default_str();
  capture_app->add_flag("--manual", capture.manual,
                        "the operator jogs the arm and adds each pose (commands on stdin)");
  capture_app->add_option("--target", capture.target,
                          "the target on the flange, recorded for register, e.g. "
                          "charuco:5x5:0.06:0.045:4x4_50 (default: the robot's marker)");
  capture_app->add_option("-o,--output", capture.output, "folder to write")->required();
  commands.push_back({capture_app, [capture_shared] {
                        return run_capture(*capture_shared, std::cout, std::cerr);
                      }});
  commands.push_back({calibrate_app, [calibrate_options] {
                        return run_calibrate(*calibrate_options, std::cout, std::cerr);
                      }});
  commands.push_back({register_app, [register_shared] {
                        return run_register(*register_shared, std::cout, std::cerr);
                      }});
  commands.push_back(
      {eval_app, [eval_shared] { return run_eval(*eval_shared, std::cout, std::cerr); }});
}

// [SECTION] sim (the simulated robot and stereo rig)

void add_sim_commands(CLI::App& app, Commands& commands) {
  CLI::App* sim_app = app.add_subcommand("sim", "the simulated robot and stereo rig");
  sim_app->require_subcommand(1);
  auto capture = std::make_shared<SimCaptureOptions>();
  SimCaptureOptions& sim_capture = *capture;
  CLI::App* sim_capture_app = sim_app->add_subcommand(
      "capture", "calibration images of a target from the simulated stereo rig + truth.yaml");
  sim_capture_app->add_option("--rig", sim_capture.rig, "rig file (data/rigs/*.yaml)")
      ->capture_default_str();
  sim_capture_app
      ->add_option("--pattern", sim_capture.pattern,
                   "chessboard:COLSxROWS:SQUARE_M, circles:COLSxROWS:SPACING_M or "
                   "charuco:SXxSY:SQUARE_M:MARKER_M:DICT")
      ->capture_default_str();
  sim_capture_app->add_option("--views", sim_capture.views, "stereo pairs to write (1..100)")
      ->capture_default_str();
  sim_capture_app->add_option("-o,--output", sim_capture.output, "directory to write to")
      ->required();
  sim_capture_app->add_option("--seed", sim_capture.seed, "seed of the poses and the noise")
      ->capture_default_str();
  sim_capture_app
      ->add_option("--noise", sim_capture.noise, "sensor noise, grey levels (Gaussian sigma)")
      ->capture_default_str();
  sim_capture_app
      ->add_option("--supersample", sim_capture.supersample,
                   "anti-aliasing samples per pixel and axis (1..8)")
      ->capture_default_str();
  sim_capture_app->add_flag("--no-scene", sim_capture.no_scene,
                            "the target alone (no robot, floor or table)");

  auto frame = std::make_shared<SimFrameOptions>();
  SimFrameOptions& sim_frame = *frame;
  CLI::App* sim_frame_app = sim_app->add_subcommand(
      "frame", "one stereo pair of the simulated scene at a joint configuration (true cameras)");
  sim_frame_app->add_option("--rig", sim_frame.rig, "rig file (data/rigs/*.yaml)")
      ->capture_default_str();
  sim_frame_app->add_option("--q", sim_frame.q, "joint values (rad, or deg with --deg) or a name")
      ->capture_default_str();
  sim_frame_app->add_flag("--deg", sim_frame.degrees, "joint values in degrees");
  sim_frame_app->add_option("--gripper", sim_frame.gripper, "gripper opening, m")
      ->capture_default_str();
  sim_frame_app->add_option("--seed", sim_frame.seed, "seed of the sensor noise");
  sim_frame_app->add_option("--noise", sim_frame.noise, "sensor noise, grey levels")
      ->capture_default_str();
  sim_frame_app
      ->add_option("--supersample", sim_frame.supersample,
                   "anti-aliasing: S x S samples averaged per pixel, 1..8")
      ->capture_default_str();
  sim_frame_app
      ->add_option("--multisample", sim_frame.multisample,
                   "anti-aliasing: MSAA samples per pixel (1..the OpenGL driver's limit)")
      ->capture_default_str();
  sim_frame_app->add_option("-o,--output", sim_frame.output, "PREFIX: writes PREFIX_left/right.png")
      ->required();

  auto observations = std::make_shared<SimObservationsOptions>();
  SimObservationsOptions& sim_observations = *observations;
  CLI::App* sim_observations_app =
      sim_app->add_subcommand("observations",
                              "registration observations: the gripper's ArUco marker detected in "
                              "rendered stereo images at random configurations");
  sim_observations_app->add_option("--rig", sim_observations.rig, "rig file (data/rigs/*.yaml)")
      ->capture_default_str();
  add_robot_arguments(sim_observations_app, sim_observations, true);
  sim_observations_app
      ->add_option("--configs", sim_observations.configs, "configurations to render (1..500)")
      ->capture_default_str();
  sim_observations_app->add_option("-o,--output", sim_observations.output, "observations YAML")
      ->required();
  sim_observations_app
      ->add_option("--seed", sim_observations.seed, "seed of the configurations and the noise")
      ->capture_default_str();
  sim_observations_app
      ->add_option("--noise", sim_observations.noise, "sensor noise, grey levels (sigma)")
      ->capture_default_str();
  sim_observations_app
      ->add_option("--supersample", sim_observations.supersample,
                   "anti-aliasing samples per pixel and axis (1..8)")
      ->capture_default_str();
  sim_observations_app->add_flag(
      "--collision-free", sim_observations.collision_free,
      "only configurations free of contact (the arm with itself and the rig's scene), as the "
      "robot server accepts them");

  commands.push_back(
      {sim_capture_app, [capture] { return run_sim_capture(*capture, std::cout, std::cerr); }});
  commands.push_back(
      {sim_frame_app, [frame] { return run_sim_frame(*frame, std::cout, std::cerr); }});
  commands.push_back({sim_observations_app, [observations] {
                        return run_sim_observations(*observations, std::cout, std::cerr);
                      }});
}

}  // namespace telear::cli
