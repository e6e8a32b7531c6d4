// The command line's conventions (apps/cli_app.hpp, docs/cli.md): the one WIDTHxHEIGHT
// validator, usage errors as one line and exit 2; and the operator's families that use them
// most, the console and the benchmarks. One of the three translation units with CLI11.

#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "apps/cli_app.hpp"
#include "apps/cli_parsing.hpp"
#include "apps/console_command.hpp"
#include "apps/web_command.hpp"
#include "bench/kin_bench_command.hpp"
#include "bench/latency_bench_command.hpp"
#include "bench/prediction_bench_command.hpp"
#include "bench/render_bench_command.hpp"
#include "bench/stream_bench_command.hpp"

namespace telear::cli {
namespace {

// The console's window (or headless frame buffer), pixels.
constexpr core::ImageSize kMinWindow{64, 48};
constexpr core::ImageSize kMaxWindow{8192, 8192};

}  // namespace

// [SECTION] console (docs/console.md)

void add_robot_arguments(CLI::App* app, geometry::RobotSelection& arguments, bool draws_meshes,
                         const std::string& robot_option) {
  app->add_option(robot_option, arguments.robot,
                  "shipped robot name, robot file (.yaml), DH table (.yaml) or URDF (.urdf)")
      ->capture_default_str();
  app->add_option("--tip", arguments.tip, "tip link of a URDF whose tree has several leaves");
  app->add_option("--package-path", arguments.package_paths,
                  "directory searched first for package:// URIs (repeatable; then the robot "
                  "file's package_paths, then ROS_PACKAGE_PATH)");
  if (draws_meshes) {
    app->add_option("--missing-meshes", arguments.missing_meshes,
                    "a mesh that cannot be found: error, or primitives (a stand-in + warning)")
        ->capture_default_str()
        ->check(CLI::IsMember({"error", "primitives"}));
  }
}

void add_console_command(CLI::App& app, Commands& commands) {
  struct ConsoleArguments {
    console::ConsoleOptions console;
    geometry::RobotSelection arm;
  };
  auto arguments = std::make_shared<ConsoleArguments>();
  console::ConsoleOptions& console = arguments->console;
  CLI::App* console_app = app.add_subcommand(
      "console", "the operator console: stereo AR view, ghost, plan, real robot (Dear ImGui)");
  console_app->add_option("--robot", console.robot, "robot server HOST:PORT (none: embedded sim)");
  console_app->add_option("--vision", console.vision,
                          "vision server HOST:PORT (none: embedded sim)");
  console_app->add_option("--token-file", console.token_file, "file whose first line is the token");
  console_app->add_option("--tls-ca", console.tls_ca_file,
                          "the servers speak TLS: trust this CA (PEM)");
  add_robot_arguments(console_app, arguments->arm, /*draws_meshes=*/true, "--arm");
  console_app->add_option("--calibration", console.calibration, "registered stereo camera file");
  console_app->add_option("--workspace", console.workspace,
                          "the scene drawn in the views (default: the robot's shipped workspace)");
  console_app->add_option("--resolution", console.resolution, "video size WIDTHxHEIGHT")
      ->capture_default_str()
      ->check(image_size_validator({64, 48}, {1920, 1080}));
  console_app
      ->add_option_function<std::string>(
          "--size",
          [arguments](const std::string& text) {
            const auto size = core::parse_image_size(text, kMinWindow, kMaxWindow);
            if (size)
              arguments->console.width = size->width, arguments->console.height = size->height;
          },
          "window size WIDTHxHEIGHT (default 1600x1000)")
      ->check(image_size_validator(kMinWindow, kMaxWindow));
  console_app->add_flag("--headless", console.headless, "EGL frame buffer, no window, no X");
  console_app->add_option("--fullscreen-eyes", console.fullscreen_eyes,
                          "two-windows or sbs: full-screen eye output (HMD, 3-D display)");
  console_app
      ->add_option("--video-planes", console.video_planes,
                   "auto, on or off: the video's colour conversion on the GPU (auto: where the "
                   "renderer is a hardware GPU)")
      ->check(CLI::IsMember({"auto", "on", "off"}));
  console_app->add_option("--screenshot", console.screenshot, "write the console's image (PNG)");
  console_app->add_option("--frames", console.frames, "stop after N frames (screenshot: 60)");
  console_app->add_option("--script", console.script, "replay UI actions (docs/console.md)");
  console_app->add_option("--record", console.record,
                          "record the session to this MCAP file (Foxglove; docs/recording.md)");
  console_app->add_option("--lease-heartbeat", console.lease_heartbeat_s,
                          "s between lease renewals asked of the robot server (0: its default)");

  commands.push_back({console_app, [arguments] {
                        return run_console(arguments->console, arguments->arm, std::cout,
                                           std::cerr);
                      }});
}

// [SECTION] web (docs/web.md)

void add_web_command(CLI::App& app, Commands& commands) {
  struct WebArguments {
    web::WebOptions web;
    geometry::RobotSelection arm;
  };
  auto arguments = std::make_shared<WebArguments>();
  web::WebOptions& web = arguments->web;
  CLI::App* web_app = app.add_subcommand(
      "web", "the operator console as a web page (three.js, WebXR): one session per browser tab");
  web_app->add_option("--listen", web.listen, "HOST:PORT the page is served on (port 0: any)")
      ->capture_default_str();
  web_app->add_option("--robot", web.robot, "robot server HOST:PORT (none: embedded sim)");
  web_app->add_option("--vision", web.vision, "vision server HOST:PORT (none: embedded sim)");
  web_app->add_option("--token-file", web.token_file,
                      "the servers' token (embedded: theirs; else: to read the cameras)");
  web_app->add_option("--tls-ca", web.tls_ca_file, "the servers speak TLS: trust this CA (PEM)");
  web_app->add_option("--tls-cert", web.tls_cert_file, "serve HTTPS: certificate chain (PEM)");
  web_app->add_option("--tls-key", web.tls_key_file, "serve HTTPS: private key (PEM)");
  add_robot_arguments(web_app, arguments->arm, /*draws_meshes=*/true, "--arm");
  web_app->add_option("--calibration", web.calibration, "registered stereo camera file");
  web_app->add_option("--workspace", web.workspace,
                      "the scene drawn in VR (default: the robot's shipped workspace)");
  web_app->add_option("--resolution", web.resolution, "video size WIDTHxHEIGHT")
      ->capture_default_str()
      ->check(image_size_validator({64, 48}, {1920, 1080}));
  web_app->add_option("--max-tabs", web.max_tabs, "browser tabs served at once (more: 503)")
      ->capture_default_str()
      ->check(CLI::Range(1, 256));
  web_app->add_option("--lease-heartbeat", web.lease_heartbeat_s,
                      "s between lease renewals asked of the robot server (0: its default)");
  commands.push_back({web_app, [arguments] {
                        return run_web(arguments->web, arguments->arm, std::cout, std::cerr);
                      }});
}

// [SECTION] replay (docs/recording.md, "Replay")

void add_replay_command(CLI::App& app, Commands& commands) {
  struct ReplayArguments {
    console::ReplayOptions replay;
    geometry::RobotSelection arm;
  };
  auto arguments = std::make_shared<ReplayArguments>();
  arguments->arm.robot.clear();  // the recording's robot unless given
  console::ReplayOptions& replay = arguments->replay;
  CLI::App* replay_app = app.add_subcommand(
      "replay", "a recording (MCAP) in the console's AR view: play, pause, seek, speed");
  replay_app->add_option("file", replay.path, "the recording, F.mcap")->required();
  add_robot_arguments(replay_app, arguments->arm, /*draws_meshes=*/true);
  replay_app->add_option("--at", replay.at, "start at this time, s from the recording's start")
      ->capture_default_str();
  replay_app->add_option("--speed", replay.speed, "playback speed, 1/16 .. 16")
      ->capture_default_str();
  replay_app->add_flag(
      "--paused", [arguments](std::int64_t) { arguments->replay.play = false; },
      "open paused (windowed)");
  replay_app
      ->add_option_function<std::string>(
          "--size",
          [arguments](const std::string& text) {
            const auto size = core::parse_image_size(text, kMinWindow, kMaxWindow);
            if (size)
              arguments->replay.width = size->width, arguments->replay.height = size->height;
          },
          "window size WIDTHxHEIGHT (default 1600x1000)")
      ->check(image_size_validator(kMinWindow, kMaxWindow));
  replay_app->add_flag("--headless", replay.headless, "EGL frame buffer, no window, no X");
  replay_app->add_option("--screenshot", replay.screenshot,
                         "write the window's image (PNG) after the last frame");
  replay_app->add_option("--frames", replay.frames,
                         "stop after N frames (headless: 1 by default, playing when > 1)");
  commands.push_back({replay_app, [arguments] {
                        return run_replay(arguments->replay, arguments->arm, std::cout, std::cerr);
                      }});
}

// [SECTION] bench (one subcommand per benchmark: render, kin, stream, prediction, latency)

void add_bench_commands(CLI::App& app, Commands& commands) {
  CLI::App* bench_app = app.add_subcommand("bench", "measured figures beside the seed's");
  bench_app->require_subcommand(1);
  auto render_options = std::make_shared<RenderBenchOptions>();
  RenderBenchOptions& bench_render_options = *render_options;
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
  bench_render->add_option("--mesh-arm", bench_render_options.mesh_arm,
                           "also a URDF mesh arm (ur6 or arm7, generated with dense meshes) in "
                           "the stereo AR frame, against the PUMA's 8-segment case");
  bench_render
      ->add_option("--mesh-detail", bench_render_options.mesh_detail,
                   "generate_arms.py --detail of the mesh arm (64: > 100k triangles)")
      ->capture_default_str();
  bench_render
      ->add_option("--mesh-tolerance", bench_render_options.mesh_tolerance_m,
                   "the mesh arm's level of detail, metres the surface may move (0: only the "
                   "arm as loaded)")
      ->check(CLI::Range(0.0, 0.01))
      ->capture_default_str();
  auto kin_options = std::make_shared<BenchKinOptions>();
  BenchKinOptions& bench_kin_options = *kin_options;
  CLI::App* bench_kin = bench_app->add_subcommand(
      "kin", "FK, Jacobian, analytic and numeric IK of any arm against Orocos KDL");
  add_robot_arguments(bench_kin, bench_kin_options, /*draws_meshes=*/false);
  bench_kin->add_option("--poses", bench_kin_options.poses, "random targets for numeric IK")
      ->capture_default_str();
  bench_kin->add_option("--json", bench_kin_options.json, "also write the table as JSON to FILE");
  auto stream_options = std::make_shared<StreamBenchOptions>();
  StreamBenchOptions& bench_stream_options = *stream_options;
  CLI::App* bench_stream = bench_app->add_subcommand(
      "stream", "stereo video and robot commands through the real servers on loopback");
  bench_stream->add_option("--seconds", bench_stream_options.seconds, "measured s per resolution")
      ->capture_default_str();
  bench_stream
      ->add_option("--resolutions", bench_stream_options.resolutions,
                   "WIDTHxHEIGHT per eye, comma-separated")
      ->capture_default_str()
      ->check(image_size_validator({16, 16}, {8192, 8192}, true));
  bench_stream
      ->add_option("--source-fps", bench_stream_options.source_fps, "synthetic source's rate")
      ->capture_default_str();
  bench_stream->add_option("--quality", bench_stream_options.quality, "JPEG quality 1..100")
      ->capture_default_str();
  bench_stream
      ->add_option("--rtt-calls", bench_stream_options.rtt_calls,
                   "robot round trips per command kind")
      ->capture_default_str();
  bench_stream->add_flag(
      "--sequential-decode", bench_stream_options.sequential_decode,
      "the client decodes the two eyes in turn (the parallel decode's baseline)");
  bench_stream->add_flag("--planes", bench_stream_options.decode_planes,
                         "the client decodes to Y'CbCr planes (no colour conversion: the "
                         "renderer's job, docs/benchmarks.md)");
  bench_stream->add_option("--json", bench_stream_options.json,
                           "also write the results as JSON to FILE");
  auto prediction_options = std::make_shared<PredictionBenchOptions>();
  PredictionBenchOptions& bench_prediction_options = *prediction_options;
  CLI::App* bench_prediction = bench_app->add_subcommand(
      "prediction", "the predicted arm against the simulator's truth under a network delay");
  bench_prediction
      ->add_option("--delay-ms", bench_prediction_options.delay_ms,
                   "video and robot state held back by this much")
      ->capture_default_str();
  bench_prediction->add_option("--moves", bench_prediction_options.moves, "moves of the plan, 1..3")
      ->capture_default_str();
  bench_prediction
      ->add_option("--speed", bench_prediction_options.speed,
                   "the plan's share of the arm's speed limits")
      ->capture_default_str();
  bench_prediction->add_option("--fps", bench_prediction_options.fps, "display ticks per second")
      ->capture_default_str();
  bench_prediction->add_option("--json", bench_prediction_options.json,
                               "also write the results as JSON to FILE");

  auto latency_options = std::make_shared<LatencyBenchOptions>();
  LatencyBenchOptions& bench_latency_options = *latency_options;
  CLI::App* bench_latency = bench_app->add_subcommand(
      "latency", "glass to glass: capture -> shown through the vision service and the AR view");
  bench_latency
      ->add_option("--resolution", bench_latency_options.resolution, "WIDTHxHEIGHT per eye")
      ->capture_default_str()
      ->check(image_size_validator({304, 64}, {8192, 8192}));
  bench_latency->add_option("--seconds", bench_latency_options.seconds, "measured seconds")
      ->capture_default_str();
  bench_latency->add_option("--fps", bench_latency_options.fps, "the source's frame rate")
      ->capture_default_str();
  bench_latency->add_option("--quality", bench_latency_options.quality, "JPEG quality 1..100")
      ->capture_default_str();
  bench_latency->add_option("--json", bench_latency_options.json,
                            "also write the results as JSON to FILE");
  commands.push_back({bench_latency, [latency_options] {
                        return run_bench_latency(*latency_options, std::cout, std::cerr);
                      }});

  commands.push_back({bench_render, [render_options] {
                        return run_bench_render(*render_options, std::cout, std::cerr);
                      }});
  commands.push_back({bench_stream, [stream_options] {
                        return run_bench_stream(*stream_options, std::cout, std::cerr);
                      }});
  commands.push_back({bench_prediction, [prediction_options] {
                        return run_bench_prediction(*prediction_options, std::cout, std::cerr);
                      }});
  commands.push_back({bench_kin, [kin_options] {
#ifdef TELEAR_HAVE_KIN_BENCH
                        return run_bench_kin(*kin_options, std::cout, std::cerr);
#else
                        std::cerr << "telear bench kin: not built (configure with "
                                     "-DTELEAR_BUILD_BENCH=ON)\n";
                        return 2;
#endif
                      }});
}

// [SECTION] validators and usage errors

CLI::Validator image_size_validator(core::ImageSize min, core::ImageSize max, bool list) {
  return CLI::Validator(image_size_check(min, max, list), list ? "WxH,..." : "WxH");
}

namespace {

// "telear kin fk": the program and the subcommands chosen so far.
std::string command_path(const CLI::App& app, const CLI::App*& deepest) {
  std::string path = app.get_name();
  deepest = &app;
  for (auto chosen = app.get_subcommands(); !chosen.empty();
       chosen = chosen.front()->get_subcommands()) {
    deepest = chosen.front();
    path += " " + deepest->get_name();
  }
  return path;
}

// The problem in one line: CLI11's text, except for what it leaves unnamed (an unknown
// subcommand or option is reported as "a subcommand is required" or as an extra argument).
std::string usage_problem(const CLI::App& app, const CLI::App& deepest,
                          const CLI::ParseError& error, const std::string& path) {
  const std::vector<std::string> left = app.remaining(true);
  if (!left.empty()) {
    const std::string& first = left.front();
    if (first.size() > 1 && first.front() == '-') {
      return "unknown option '" + first + "' (" + path + " --help lists the options)";
    }
    if (deepest.get_require_subcommand_min() == 0) return "unexpected argument '" + first + "'";
    return "unknown subcommand '" + first + "' (" + path + " --help lists them)";
  }
  std::string message = error.what();
  if (message == "A subcommand is required") {
    message = "a subcommand is required (" + path + " --help lists them)";
  }
  const std::string unconverted = "Could not convert: ";  // "Could not convert: --views = x"
  if (error.get_name() == "ConversionError" && message.rfind(unconverted, 0) == 0) {
    const std::string rest = message.substr(unconverted.size());
    const auto equals = rest.find(" = ");
    if (equals != std::string::npos) {
      message = rest.substr(0, equals) + ": '" + rest.substr(equals + 3) +
                "' is not a valid value (see --help)";
    }
  }
  const std::string missing = " missing";  // "--q: 1 required TEXT missing"
  if (error.get_name() == "ArgumentMismatch" && message.size() > missing.size() &&
      message.compare(message.size() - missing.size(), missing.size(), missing) == 0) {
    message = message.substr(0, message.find(':')) + " needs a value";
  }
  for (char& c : message) {
    if (c == '\n') c = ' ';
  }
  return message;
}

}  // namespace

int report_parse_error(const CLI::App& app, const CLI::ParseError& error, std::ostream& out,
                       std::ostream& err) {
  if (error.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) {
    return app.exit(error, out, err);  // --help, --version
  }
  const CLI::App* deepest = nullptr;
  const std::string path = command_path(app, deepest);
  err << path << ": " << usage_problem(app, *deepest, error, path) << "\n";
  return 2;
}
}  // namespace telear::cli
