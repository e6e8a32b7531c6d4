// telear's command line. CLI11 is included in this translation unit only (it is slow to
// compile); each subcommand's work lives in its own *_command.cpp without CLI11.

#include <CLI/CLI.hpp>
#include <iostream>
#include <sstream>

#include "apps/bench_command.hpp"
#include "apps/calibrate_command.hpp"
#include "apps/console_command.hpp"
#include "apps/demo_command.hpp"
#include "apps/eval_command.hpp"
#include "apps/kin_command.hpp"
#include "apps/register_command.hpp"
#include "apps/render_bench_command.hpp"
#include "apps/render_command.hpp"
#include "apps/robot_server_command.hpp"
#include "apps/sim_command.hpp"
#include "apps/sim_frame_command.hpp"
#include "apps/sim_observations_command.hpp"
#include "apps/stream_bench_command.hpp"
#include "apps/vision_server_command.hpp"
#include "telear/core/version.hpp"

int main(int argc, char** argv) {
  CLI::App app{"telear: augmented-reality telerobotics (docs/cli.md)", "telear"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "telear " + std::string(telear::core::version_string()));

  // [SECTION] demo (the README's main command; docs/demo.md)
  telear::cli::DemoOptions demo;
  CLI::App* demo_app = app.add_subcommand(
      "demo", "the whole workflow on the simulated robot and rig: rehearse, preview, execute");
  demo_app->add_option("--out", demo.out, "output folder (video, key frames, report)")
      ->capture_default_str();
  demo_app->add_option("--cache", demo.cache, "calibration cache folder (default OUT/cache)");
  demo_app->add_option("--resolution", demo.resolution, "stereo video size WIDTHxHEIGHT per eye")
      ->capture_default_str();
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
  demo_app->add_flag("--no-video", demo.no_video, "skip the MP4 (key frames and report only)");

  // [SECTION] kin
  telear::cli::KinOptions kin;
  CLI::App* kin_app = app.add_subcommand("kin", "the arm's geometric model: FK, IK, limits");
  kin_app->require_subcommand(1);
  auto add_robot = [&kin](CLI::App* sub) {
    sub->add_option("--robot", kin.robot, "shipped robot name or .yaml / .urdf file")
        ->capture_default_str();
  };
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

  // [SECTION] render
  telear::cli::RenderOptions render;
  CLI::App* render_app =
      app.add_subcommand("render", "draw the arm through a camera, on a video frame, to PNG");
  render_app->add_option("--robot", render.robot, "shipped robot name or .yaml / .urdf file")
      ->capture_default_str();
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

  // [SECTION] calibrate
  telear::cli::CalibrateOptions calibrate;
  CLI::App* calibrate_app = app.add_subcommand(
      "calibrate", "camera calibration, mono or stereo, from images of a chessboard or circles");
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
                   "circles:COLSxROWS:SPACING_M (asymmetric grid)")
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
  calibrate_app->add_flag("--estimate-k3", calibrate.estimate_k3,
                          "estimate k3 too (default: held at 0, two radial terms)");
  calibrate_app->add_flag("--zero-tangential", calibrate.zero_tangential, "hold p1, p2 at 0");
  calibrate_app->add_flag("--keep-mono-intrinsics", calibrate.keep_mono_intrinsics,
                          "stereo: keep each camera's own calibration, fit only R, T");

  // [SECTION] register
  telear::cli::RegisterOptions register_options;
  CLI::App* register_app = app.add_subcommand(
      "register", "the robot base's pose in each camera (T_cam_base) from marker observations");
  register_app
      ->add_option("--rig", register_options.rig,
                   "stereo camera file with R, T (telear calibrate's output)")
      ->required();
  register_app->add_option("--robot", register_options.robot, "shipped robot name or file")
      ->capture_default_str();
  register_app
      ->add_option("--observations", register_options.observations,
                   "observations YAML (telear sim observations)")
      ->required();
  register_app->add_option("-o,--output", register_options.output, "camera file to write")
      ->required();
  register_app
      ->add_option("--max-iterations", register_options.max_iterations,
                   "Levenberg-Marquardt iterations at most")
      ->capture_default_str();

  // [SECTION] eval
  telear::cli::EvalOptions eval_options;
  CLI::App* eval_app = app.add_subcommand(
      "eval", "accuracy of calibration + registration against ground truth (sim)");
  eval_app->add_option("--truth", eval_options.truth, "true stereo cameras (sim truth.yaml)")
      ->required();
  eval_app->add_option("--estimate", eval_options.estimate, "registered stereo camera file")
      ->required();
  eval_app->add_option("--robot", eval_options.robot, "shipped robot name or file")
      ->capture_default_str();
  eval_app->add_option("--json", eval_options.json, "also write the table as JSON to FILE");
  eval_app
      ->add_option("--configurations", eval_options.configurations,
                   "random arm configurations of the overlay error")
      ->capture_default_str();
  eval_app->add_option("--spacing", eval_options.spacing_m, "body sample spacing, m")
      ->capture_default_str();

  // [SECTION] sim (the simulated robot and stereo rig)
  CLI::App* sim_app = app.add_subcommand("sim", "the simulated robot and stereo rig");
  sim_app->require_subcommand(1);
  telear::cli::SimCaptureOptions sim_capture;
  CLI::App* sim_capture_app = sim_app->add_subcommand(
      "capture", "calibration images of a target from the simulated stereo rig + truth.yaml");
  sim_capture_app->add_option("--rig", sim_capture.rig, "rig file (data/rigs/*.yaml)")
      ->capture_default_str();
  sim_capture_app
      ->add_option("--pattern", sim_capture.pattern,
                   "chessboard:COLSxROWS:SQUARE_M or circles:COLSxROWS:SPACING_M")
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

  telear::cli::SimFrameOptions sim_frame;
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
  sim_frame_app->add_option("-o,--output", sim_frame.output, "PREFIX: writes PREFIX_left/right.png")
      ->required();

  telear::cli::SimObservationsOptions sim_observations;
  CLI::App* sim_observations_app =
      sim_app->add_subcommand("observations",
                              "registration observations: the gripper's ArUco marker detected in "
                              "rendered stereo images at random configurations");
  sim_observations_app->add_option("--rig", sim_observations.rig, "rig file (data/rigs/*.yaml)")
      ->capture_default_str();
  sim_observations_app->add_option("--robot", sim_observations.robot, "shipped robot name or file")
      ->capture_default_str();
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

  // [SECTION] robot-server (docs/network.md)
  telear::cli::RobotServerCommandOptions robot_server;
  CLI::App* robot_server_app = app.add_subcommand(
      "robot-server", "the robot service over gRPC, the simulated robot as its driver");
  robot_server_app->add_option("--listen", robot_server.listen, "HOST:PORT; port 0: ephemeral")
      ->capture_default_str();
  robot_server_app
      ->add_option("--token-file", robot_server.token_file,
                   "file whose first line is the bearer token commands must carry")
      ->required();
  robot_server_app->add_flag("--allow-observers,!--no-observers", robot_server.allow_observers,
                             "state readable without a token (default) or not");
  robot_server_app->add_option("--tls-cert", robot_server.tls_cert, "TLS certificate (PEM)");
  robot_server_app->add_option("--tls-key", robot_server.tls_key, "TLS private key (PEM)");
  robot_server_app->add_option("--robot", robot_server.robot, "shipped robot name or file")
      ->capture_default_str();
  robot_server_app
      ->add_option("--heartbeat-ms", robot_server.heartbeat_ms,
                   "default lease heartbeat period: a lease not renewed within it stops the arm")
      ->capture_default_str();
  robot_server_app->add_option("--q", robot_server.initial_q,
                               "initial joint values (rad) or a named configuration");
  robot_server_app->add_option("--log-level", robot_server.log_level,
                               "trace, debug, info, warn, error or off");

  // [SECTION] vision-server (docs/network.md)
  telear::cli::VisionServerCommandOptions vision_server;
  CLI::App* vision_server_app = app.add_subcommand(
      "vision-server", "the stereo vision stream over gRPC (sim rig, video files, cameras)");
  vision_server_app->add_option("--listen", vision_server.listen, "HOST:PORT; port 0: ephemeral")
      ->capture_default_str();
  vision_server_app->add_option("--source", vision_server.source, "sim, files, v4l2 or synthetic")
      ->capture_default_str();
  vision_server_app->add_option("--rig", vision_server.rig, "sim: rig file (data/rigs/*.yaml)")
      ->capture_default_str();
  vision_server_app->add_option("--robot-server", vision_server.robot_server,
                                "sim: HOST:PORT of the robot server whose state the arm follows");
  vision_server_app->add_option("--token-file", vision_server.token_file,
                                "calls need this bearer token (also sent to the robot server)");
  vision_server_app->add_option("--robot-token-file", vision_server.robot_token_file,
                                "token for the robot server, when it differs");
  vision_server_app->add_option("--left", vision_server.left, "files: the left eye's video");
  vision_server_app->add_option("--right", vision_server.right, "files: the right eye's video");
  vision_server_app->add_option("--cameras", vision_server.cameras, "v4l2: L,R device indices")
      ->capture_default_str();
  vision_server_app->add_option("--calibration", vision_server.calibration,
                                "stereo camera file returned by GetCameraInfo");
  vision_server_app->add_option("--fps", vision_server.fps,
                                "capture rate (0: the source's default, 30 or a file's own)");
  vision_server_app->add_option("--resolution", vision_server.resolution,
                                "WxH capture size (v4l2, files, synthetic)");
  vision_server_app->add_option("--quality", vision_server.quality, "JPEG quality 1..100")
      ->capture_default_str();
  vision_server_app
      ->add_option("--supersample", vision_server.supersample,
                   "sim: anti-aliasing samples per pixel and axis (1..8)")
      ->capture_default_str();
  vision_server_app->add_option("--noise", vision_server.noise, "sim: sensor noise, grey levels")
      ->capture_default_str();
  vision_server_app->add_option("--log-level", vision_server.log_level,
                                "trace, debug, info, warn, error or off");

  // [SECTION] console (docs/console.md)
  telear::console::ConsoleOptions console;
  std::string console_size;
  CLI::App* console_app = app.add_subcommand(
      "console", "the operator console: stereo AR view, ghost, plan, real robot (Dear ImGui)");
  console_app->add_option("--robot", console.robot, "robot server HOST:PORT (none: embedded sim)");
  console_app->add_option("--vision", console.vision,
                          "vision server HOST:PORT (none: embedded sim)");
  console_app->add_option("--token-file", console.token_file, "file whose first line is the token");
  console_app->add_option("--calibration", console.calibration, "registered stereo camera file");
  console_app->add_option("--workspace", console.workspace,
                          "the scene drawn in the views (default: the robot's shipped workspace)");
  console_app->add_option("--resolution", console.resolution, "video size WxH")
      ->capture_default_str();
  console_app->add_option("--size", console_size, "window size WxH (default 1600x1000)");
  console_app->add_flag("--headless", console.headless, "EGL frame buffer, no window, no X");
  console_app->add_option("--fullscreen-eyes", console.fullscreen_eyes,
                          "two-windows or sbs: full-screen eye output (HMD, 3-D display)");
  console_app->add_option("--screenshot", console.screenshot, "write the console's image (PNG)");
  console_app->add_option("--frames", console.frames, "stop after N frames (screenshot: 60)");
  console_app->add_option("--script", console.script, "replay UI actions (docs/console.md)");

  // [SECTION] bench (one subcommand per benchmark: render, ...)
  CLI::App* bench_app = app.add_subcommand("bench", "measured figures beside the seed's");
  bench_app->require_subcommand(1);
  telear::cli::RenderBenchOptions bench_render_options;
  CLI::App* bench_render =
      bench_app->add_subcommand("render", "the seed's rendering Tables 1 and 2, headless (EGL)");
  bench_render->add_option("--seconds", bench_render_options.seconds, "timed seconds per case")
      ->capture_default_str();
  bench_render->add_option("--width", bench_render_options.width, "view width in pixels")
      ->capture_default_str();
  bench_render->add_option("--height", bench_render_options.height, "view height in pixels")
      ->capture_default_str();
  bench_render->add_option("--only", bench_render_options.only,
                           "run only the cases whose name contains this text");
  bench_render->add_flag("--json", bench_render_options.json, "print JSON");
  telear::cli::BenchKinOptions bench_kin_options;
  CLI::App* bench_kin =
      bench_app->add_subcommand("kin", "FK, Jacobian, analytic and numeric IK against Orocos KDL");
  bench_kin->add_option("--robot", bench_kin_options.robot, "shipped robot name or DH .yaml file")
      ->capture_default_str();
  bench_kin->add_option("--poses", bench_kin_options.poses, "random targets for numeric IK")
      ->capture_default_str();
  bench_kin->add_option("--json", bench_kin_options.json, "also write the table as JSON to FILE");
  telear::cli::StreamBenchOptions bench_stream_options;
  CLI::App* bench_stream = bench_app->add_subcommand(
      "stream", "stereo video and robot commands through the real servers on loopback");
  bench_stream->add_option("--seconds", bench_stream_options.seconds, "measured s per resolution")
      ->capture_default_str();
  bench_stream
      ->add_option("--resolutions", bench_stream_options.resolutions,
                   "WxH per eye, comma-separated")
      ->capture_default_str();
  bench_stream
      ->add_option("--source-fps", bench_stream_options.source_fps, "synthetic source's rate")
      ->capture_default_str();
  bench_stream->add_option("--quality", bench_stream_options.quality, "JPEG quality 1..100")
      ->capture_default_str();
  bench_stream
      ->add_option("--rtt-calls", bench_stream_options.rtt_calls,
                   "robot round trips per command kind")
      ->capture_default_str();
  bench_stream->add_option("--json", bench_stream_options.json,
                           "also write the results as JSON to FILE");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }

  if (demo_app->parsed()) return telear::cli::run_demo(demo, std::cout, std::cerr);
  if (kin_info->parsed()) return telear::cli::run_kin_info(kin, std::cout, std::cerr);
  if (kin_fk->parsed()) return telear::cli::run_kin_fk(kin, std::cout, std::cerr);
  if (kin_demo->parsed()) return telear::cli::run_kin_demo(kin, std::cout, std::cerr);
  if (kin_ik->parsed()) return telear::cli::run_kin_ik(kin, std::cout, std::cerr);
  if (render_app->parsed()) return telear::cli::run_render(render, std::cout, std::cerr);
  if (calibrate_app->parsed()) return telear::cli::run_calibrate(calibrate, std::cout, std::cerr);
  if (sim_capture_app->parsed()) {
    return telear::cli::run_sim_capture(sim_capture, std::cout, std::cerr);
  }
  if (sim_frame_app->parsed()) return telear::cli::run_sim_frame(sim_frame, std::cout, std::cerr);
  if (register_app->parsed()) {
    return telear::cli::run_register(register_options, std::cout, std::cerr);
  }
  if (eval_app->parsed()) return telear::cli::run_eval(eval_options, std::cout, std::cerr);
  if (sim_observations_app->parsed()) {
    return telear::cli::run_sim_observations(sim_observations, std::cout, std::cerr);
  }
  if (robot_server_app->parsed()) {
    return telear::cli::run_robot_server(robot_server, std::cout, std::cerr);
  }
  if (vision_server_app->parsed()) {
    return telear::cli::run_vision_server(vision_server, std::cout, std::cerr);
  }
  if (console_app->parsed()) {
    if (!console_size.empty()) {
      char x = 0;
      std::istringstream in(console_size);
      if (!(in >> console.width >> x >> console.height) || x != 'x' || !in.eof()) {
        std::cerr << "telear console: --size '" << console_size << "' must be WIDTHxHEIGHT\n";
        return 2;
      }
    }
    return telear::cli::run_console(console, std::cout, std::cerr);
  }
  if (bench_render->parsed()) {
    return telear::cli::run_bench_render(bench_render_options, std::cout, std::cerr);
  }
  if (bench_stream->parsed()) {
    return telear::cli::run_bench_stream(bench_stream_options, std::cout, std::cerr);
  }
  if (bench_kin->parsed()) {
#ifdef TELEAR_HAVE_KIN_BENCH
    return telear::cli::run_bench_kin(bench_kin_options, std::cout, std::cerr);
#else
    std::cerr << "telear bench kin: not built (configure with -DTELEAR_BUILD_BENCH=ON)\n";
    return 2;
#endif
  }
  return 1;
}
