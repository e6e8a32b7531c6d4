// telear's command line: the program, its subcommand families (apps/cli_app.hpp; the
// servers' here) and the conventions of docs/cli.md: a usage error is one line on stderr
// and exit 2, --help and --version exit 0. CLI11 is included here, in cli_commands.cpp and
// in cli_conventions.cpp only (it is slow to compile); each subcommand's work lives in its
// *_command.cpp.

#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>

#include "apps/cli_app.hpp"
#include "apps/robot_server_command.hpp"
#include "apps/vision_server_command.hpp"
#include "telear/core/version.hpp"

namespace telear::cli {
namespace {

// [SECTION] robot-server (docs/network.md)

void add_robot_server_command(CLI::App& app, Commands& commands) {
  auto options = std::make_shared<RobotServerCommandOptions>();
  RobotServerCommandOptions& robot_server = *options;
  CLI::App* robot_server_app = app.add_subcommand(
      "robot-server", "the robot service over gRPC, driving the simulated robot or a ROS arm");
  robot_server_app->add_option("--listen", robot_server.listen, "HOST:PORT; port 0: ephemeral")
      ->capture_default_str();
  robot_server_app
      ->add_option("--token-file", robot_server.token_file,
                   "file whose first line is the bearer token commands must carry")
      ->required();
  robot_server_app->add_flag("--allow-observers,!--no-observers", robot_server.allow_observers,
                             "info and state readable without any token (default: not)");
  robot_server_app->add_option(
      "--observer-token-file", robot_server.observer_token_file,
      "a read-only token (info, state) for watchers: recorders, dashboards");
  robot_server_app->add_option("--tls-cert", robot_server.tls_cert, "TLS certificate (PEM)");
  robot_server_app->add_option("--tls-key", robot_server.tls_key, "TLS private key (PEM)");
  add_robot_arguments(robot_server_app, robot_server, false);
  robot_server_app
      ->add_option("--driver", robot_server.driver,
                   "sim (the simulated robot), ros1 (an arm driven through ROS 1, docs/ros.md) or "
                   "ros2 (a ros2_control arm over DDS, docs/ros2.md)")
      ->capture_default_str();
  robot_server_app->add_option("--ros-master", robot_server.ros.master_uri,
                               "ros1: the master's URI (default: $ROS_MASTER_URI)");
  robot_server_app
      ->add_option("--joint-states", robot_server.ros.joint_states_topic,
                   "ros1: the arm's sensor_msgs/JointState topic")
      ->capture_default_str();
  robot_server_app
      ->add_option("--controller", robot_server.ros.controller_ns,
                   "ros1: the control_msgs/FollowJointTrajectory action namespace")
      ->capture_default_str();
  robot_server_app->add_option("--gripper-action", robot_server.ros.gripper_ns,
                               "ros1: a control_msgs/GripperCommand action namespace (optional)");
  robot_server_app->add_option("--ros-domain", robot_server.ros2.domain_id,
                               "ros2: the ROS domain id, 0..232 (default: $ROS_DOMAIN_ID or 0)");
  robot_server_app
      ->add_option("--ros2-joint-states", robot_server.ros2.joint_states_topic,
                   "ros2: the arm's sensor_msgs/msg/JointState topic")
      ->capture_default_str();
  robot_server_app
      ->add_option("--ros2-controller", robot_server.ros2.controller,
                   "ros2: the JointTrajectoryController whose ~/joint_trajectory topic takes "
                   "the trajectories")
      ->capture_default_str();
  robot_server_app
      ->add_option("--heartbeat-ms", robot_server.heartbeat_ms,
                   "default lease heartbeat period: a lease not renewed within it stops the arm")
      ->capture_default_str();
  robot_server_app->add_option("--q", robot_server.initial_q,
                               "initial joint values (rad) or a named configuration");
  robot_server_app->add_option("--log-level", robot_server.log_level,
                               "trace, debug, info, warn, error or off");
  robot_server_app->add_option(
      "--workspace", robot_server.workspace,
      "workspace YAML every motion is checked against (and GetInfo hands to clients)");
  robot_server_app
      ->add_option("--safety-margin", robot_server.safety_margin_m,
                   "m: jogs keep every link at least this far from workspace objects")
      ->capture_default_str();
  robot_server_app->add_flag("--exact-meshes", robot_server.exact_meshes,
                             "check mesh links by their triangles, not their parts' convex hulls "
                             "(slower; the hulls err on the safe side: docs/collision.md)");
  commands.push_back(
      {robot_server_app, [options] { return run_robot_server(*options, std::cout, std::cerr); }});
}

// [SECTION] vision-server (docs/network.md)

void add_vision_server_command(CLI::App& app, Commands& commands) {
  auto options = std::make_shared<VisionServerCommandOptions>();
  VisionServerCommandOptions& vision_server = *options;
  CLI::App* vision_server_app = app.add_subcommand(
      "vision-server", "the stereo vision stream over gRPC (sim rig, video files, cameras)");
  vision_server_app->add_option("--listen", vision_server.listen, "HOST:PORT; port 0: ephemeral")
      ->capture_default_str();
  vision_server_app
      ->add_option("--source", vision_server.source,
                   "sim, files, v4l2, synthetic or ros (ROS 1 camera topics, docs/ros.md)")
      ->capture_default_str();
  vision_server_app->add_option("--rig", vision_server.rig, "sim: rig file (data/rigs/*.yaml)")
      ->capture_default_str();
  vision_server_app->add_option("--robot-server", vision_server.robot_server,
                                "sim: HOST:PORT of the robot server whose state the arm follows");
  vision_server_app->add_option("--token-file", vision_server.token_file,
                                "calls need this bearer token (also sent to the robot server)");
  vision_server_app->add_option("--robot-token-file", vision_server.robot_token_file,
                                "token for the robot server, when it differs");
  vision_server_app->add_option("--observer-token-file", vision_server.observer_token_file,
                                "a second token the stream accepts (the watchers' read-only one)");
  vision_server_app->add_option("--tls-cert", vision_server.tls_cert, "TLS certificate (PEM)");
  vision_server_app->add_option("--tls-key", vision_server.tls_key, "TLS private key (PEM)");
  vision_server_app->add_option("--left", vision_server.left,
                                "files: the left eye's video; ros: its image topic");
  vision_server_app->add_option("--right", vision_server.right,
                                "files: the right eye's video; ros: its image topic");
  vision_server_app->add_option("--ros-master", vision_server.ros_master,
                                "ros: the master's URI (default: $ROS_MASTER_URI)");
  vision_server_app
      ->add_option("--sync-tolerance-ms", vision_server.sync_tolerance_ms,
                   "ros: the largest stamp difference of a left-right pair")
      ->capture_default_str();
  vision_server_app->add_option("--cameras", vision_server.cameras, "v4l2: L,R device indices")
      ->capture_default_str();
  vision_server_app->add_option(
      "--calibration", vision_server.calibration,
      "stereo camera file returned by GetCameraInfo (ros: instead of the cameras' camera_info)");
  vision_server_app->add_option(
      "--fps", vision_server.fps,
      "capture rate (0: the source's default, 30 or a file's own; ros: the rate reported, 0 "
      "measured)");
  vision_server_app
      ->add_option("--resolution", vision_server.resolution,
                   "WIDTHxHEIGHT capture size (v4l2, files, synthetic)")
      ->check(image_size_validator({16, 16}, {8192, 8192}));
  vision_server_app->add_option("--quality", vision_server.quality, "JPEG quality 1..100")
      ->capture_default_str();
  vision_server_app
      ->add_option("--supersample", vision_server.supersample,
                   "sim: anti-aliasing samples per pixel and axis (1..8)")
      ->capture_default_str();
  vision_server_app->add_option("--noise", vision_server.noise, "sim: sensor noise, grey levels")
      ->capture_default_str();
  vision_server_app->add_flag("--frame-code", vision_server.frame_code,
                              "sim, synthetic: write each frame's number and capture time into "
                              "its pixels (glass-to-glass latency, docs/latency.md)");
  vision_server_app->add_option("--log-level", vision_server.log_level,
                                "trace, debug, info, warn, error or off");
  commands.push_back(
      {vision_server_app, [options] { return run_vision_server(*options, std::cout, std::cerr); }});
}

}  // namespace
}  // namespace telear::cli

int main(int argc, char** argv) {
  CLI::App app{"telear: augmented-reality telerobotics (docs/cli.md)", "telear"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "telear " + std::string(telear::core::version_string()));

  telear::cli::Commands commands;
  telear::cli::add_demo_command(app, commands);
  telear::cli::add_kin_commands(app, commands);
  telear::cli::add_render_command(app, commands);
  telear::cli::add_plan_commands(app, commands);
  telear::cli::add_robot_commands(app, commands);
  telear::cli::add_calibration_commands(app, commands);
  telear::cli::add_sim_commands(app, commands);
  telear::cli::add_robot_server_command(app, commands);
  telear::cli::add_vision_server_command(app, commands);
  telear::cli::add_console_command(app, commands);
  telear::cli::add_web_command(app, commands);
  telear::cli::add_record_command(app, commands);
  telear::cli::add_replay_command(app, commands);
  telear::cli::add_report_command(app, commands);
  telear::cli::add_bench_commands(app, commands);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return telear::cli::report_parse_error(app, e, std::cout, std::cerr);
  }
  for (const telear::cli::Command& command : commands) {
    if (command.app->parsed()) return command.run();
  }
  return 1;  // unreachable: require_subcommand(1) on every family
}
