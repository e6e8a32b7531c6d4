#include "apps/capture_command.hpp"

#include <cmath>
#include <iostream>
#include <memory>
#include <optional>
#include <ostream>
#include <sstream>
#include <vector>

#include "apps/command_failure.hpp"
#include "telear/core/angles.hpp"
#include "telear/core/marker_mount.hpp"
#include "telear/core/number_format.hpp"
#include "telear/core/number_list.hpp"
#include "telear/core/robot_loader.hpp"
#include "telear/net/token_file.hpp"
#include "telear/session/capture_session.hpp"
#include "telear/session/registration_capture.hpp"
#include "telear/vision/capture_observations.hpp"
#include "telear/vision/image_file.hpp"
#include "telear/vision/registration_target.hpp"

namespace telear::cli {
namespace {

// [SECTION] --manual

constexpr double kJogValidityS = 2.0;  // one typed step is a whole jog: long enough to finish it
// The lease's heartbeat: the arm moves only for a typed step, each a 2 s jog at most, so a
// 1 s period (the dead-man acting within ~1.2 s, as the console's embedded default) costs no
// safety and keeps a loaded machine from stopping a step short.
constexpr double kLeaseHeartbeatS = 1.0;

const char* kManualHelp =
    "  j N D      jog joint N (from 1) by D degrees (mm for a prismatic joint), e.g. j 2 +5\n"
    "  x|y|z D    move the tool D mm along the base's x, y or z axis, e.g. z -20\n"
    "  a, Enter   add the pose the arm is at (waits until it is at rest)\n"
    "  s          solve with the poses so far (the folder stays open)\n"
    "  q          finish (the folder is complete after every pose)\n"
    "  h          these commands\n";

std::vector<std::string> words_of(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

// Sends one jog; a lease that lapsed while the operator was typing is taken again once (the
// typed command shows the operator is there), saying so.
void jog(net::RobotClient& robot, const core::MotionCommand& command, std::ostream& out) {
  auto ack = robot.jog(command, kJogValidityS);
  if (!ack && ack.error().message.find("lease lapsed") != std::string::npos) {
    out << "the lease had lapsed: taking it again\n";
    if (Status s = robot.acquire_lease(kLeaseHeartbeatS); !s) {
      out << "lease: " << s.error().message << "\n";
      return;
    }
    ack = robot.jog(command, kJogValidityS);
  }
  if (!ack) {
    out << "jog refused: " << ack.error().message << "\n";
    return;
  }
  out << "jog: target";
  for (int j = 0; j < ack->target_q.size(); ++j) {
    out << " " << core::format_fixed(core::degrees_from_radians(ack->target_q[j]), 2);
  }
  out << " deg\n";
  if (!ack->singularity_warning.empty()) out << "warning: " << ack->singularity_warning << "\n";
}

void print_pose(const session::CaptureSession& capture, const session::CapturedPoseReport& pose,
                std::ostream& out) {
  const vision::CaptureObservations& detected = capture.detected();
  out << pose.summary() << " (" << capture.poses().size() << " poses, " << pose.target << " in "
      << detected.left_found << " left / " << detected.right_found << " right)\n";
  for (const std::string& note : pose.notes) out << "  " << note << "\n";
}

// What both captures start from: the servers and the folder given, the arm, its marker mount
// and the target on the flange (--target, else the mount's marker; the mount says where either
// sits). Errors name the option.
struct CaptureArm {
  core::RobotModelPtr model;
  core::MarkerMount marker;
  vision::RegistrationTarget target;
};

Result<CaptureArm> capture_arm(const CaptureOptions& options) {
  if (options.robot_server.empty()) return Error{"--robot: give the robot server HOST:PORT"};
  if (options.vision_server.empty()) return Error{"--vision: give the vision server HOST:PORT"};
  if (options.output.empty()) return Error{"-o: give the folder to write"};
  auto model = core::load_robot(options.robot_spec());
  if (!model) return Error{"--arm: " + model.error().message};
  auto marker = core::marker_mount_for(**model);
  if (!marker) return Error{"marker: " + marker.error().message};
  CaptureArm arm{*model, *marker, vision::registration_target_from_mount(*marker)};
  if (!options.target.empty()) {
    auto parsed = vision::parse_registration_target(options.target);
    if (!parsed) return Error{"--target: " + parsed.error().message};
    arm.target = *parsed;
  }
  return arm;
}

// The robot and vision clients both captures use, started, with the token file's token.
struct Clients {
  std::unique_ptr<net::RobotClient> robot;
  std::unique_ptr<net::VisionClient> vision;
};

Result<Clients> connect(const CaptureOptions& options) {
  std::string token;
  if (!options.token_file.empty()) {
    auto t = net::load_token_file(options.token_file);
    if (!t) return Error{"--token-file: " + t.error().message};
    token = *t;
  }
  net::RobotClientOptions robot_options;
  robot_options.address = options.robot_server;
  robot_options.token = token;
  robot_options.client_name = "telear-capture";
  Clients clients;
  clients.robot = std::make_unique<net::RobotClient>(robot_options);
  clients.robot->start();
  net::VisionClientOptions vision_options;
  vision_options.address = options.vision_server;
  vision_options.token = token;
  vision_options.client_name = "telear-capture";
  vision_options.jpeg_quality = 100;  // the least loss the stream offers, at the source's size
  clients.vision = std::make_unique<net::VisionClient>(vision_options);
  clients.vision->start();
  return clients;
}

}  // namespace

int run_manual_capture(const CaptureOptions& options, std::istream& in, std::ostream& out,
                       std::ostream& err) {
  const CommandFailure fail{err, "telear capture"};
  auto loaded = capture_arm(options);
  if (!loaded) return fail(loaded.error().message);
  const vision::RegistrationTarget& target = loaded->target;
  session::CaptureSessionOptions capture_options;
  capture_options.directory = options.output;
  capture_options.frames_per_pose = options.frames;
  capture_options.settle_s = options.settle_s;
  capture_options.marker = loaded->marker;
  capture_options.target = target;
  if (Status s = capture_options.validate(); !s) return fail(s.error().message);
  auto clients = connect(options);
  if (!clients) return fail(clients.error().message);
  net::RobotClient& robot = *clients->robot;
  net::VisionClient& vision = *clients->vision;

  const core::RobotModel& arm = *loaded->model;
  auto opened = session::CaptureSession::open(arm, robot, vision, capture_options);
  if (!opened) return fail(opened.error().message, 1);
  session::CaptureSession& capture = **opened;
  if (Status s = robot.acquire_lease(kLeaseHeartbeatS); !s)
    return fail("lease: " + s.error().message, 1);
  const std::string noun = target.is_board() ? "board" : "marker";
  out << "manual capture into " << options.output << " (" << arm.name() << ", "
      << target.description() << "): jog the arm until both cameras see the " << noun
      << ", add the pose, and repeat over the images, turning the wrist\n"
      << kManualHelp << std::flush;

  for (std::string line; std::getline(in, line);) {
    const std::vector<std::string> w = words_of(line.substr(0, line.find('#')));
    const std::string verb = w.empty() ? "a" : w[0];
    if (verb == "q") break;
    if (verb == "h" || verb == "?") {
      out << kManualHelp;
    } else if (verb == "a") {
      out << "adding pose " << capture.poses().size() << " ...\n" << std::flush;
      auto added = capture.add_current_pose();
      if (added) {
        print_pose(capture, *added, out);
      } else {
        out << "not added: " << added.error().message << "\n";
      }
    } else if (verb == "s") {
      out << "solving with " << capture.poses().size() << " poses ...\n" << std::flush;
      auto solved = capture.solve();
      if (solved) {
        out << vision::capture_registration_report(*solved);
      } else {
        out << "not solved: " << solved.error().message << "\n";
      }
    } else if (verb == "j" && w.size() == 3) {
      const auto joint = core::parse_number(w[1], "N");
      const auto delta = core::parse_number(w[2], "D");
      if (!joint || *joint != std::floor(*joint) || *joint < 1 || *joint > arm.dof() || !delta) {
        out << "'" << line << "': j N D with N 1.." << arm.dof() << " and D a number\n";
      } else {
        const int j = static_cast<int>(*joint) - 1;
        const bool prismatic = arm.joint(j).type == core::JointType::kPrismatic;
        jog(robot,
            core::JointIncrement{j,
                                 prismatic ? *delta / 1000.0 : core::radians_from_degrees(*delta)},
            out);
      }
    } else if ((verb == "x" || verb == "y" || verb == "z") && w.size() == 2) {
      const auto delta = core::parse_number(w[1], "D");
      if (!delta) {
        out << "'" << line << "': " << verb << " D with D in mm\n";
      } else {
        core::CartesianIncrement step;
        step.frame = core::MotionFrame::kBase;
        step.dX[verb[0] - 'x'] = *delta / 1000.0;
        jog(robot, step, out);
      }
    } else {
      out << "'" << line << "': unknown command (h: the commands)\n";
    }
    out << std::flush;
  }
  (void)robot.release_lease();

  if (capture.poses().empty()) {
    return fail("no pose was added: nothing to register (" + options.output + ")", 1);
  }
  const std::string coverage = options.output + "/coverage.png";
  if (vision::write_png_file(coverage, capture.coverage())) {
    out << "coverage: the " << noun << " found at " << capture.detected().left_found
        << " (left) and " << capture.detected().right_found << " (right) of "
        << capture.poses().size() << " poses; " << coverage << "\n";
  }
  out << "wrote " << options.output << "/capture.yaml (" << capture.poses().size()
      << " poses); register with: telear register --captures " << options.output << " --robot "
      << options.robot_spec().name_or_path << " -o registered.yaml\n";
  return 0;
}

int run_capture(const CaptureOptions& options, std::ostream& out, std::ostream& err) {
  const CommandFailure fail{err, "telear capture"};
  if (options.manual) return run_manual_capture(options, std::cin, out, err);
  // The target is detected for automatic poses and recorded in the folder for `register`.
  auto loaded = capture_arm(options);
  if (!loaded) return fail(loaded.error().message);
  const core::RobotModel& arm = *loaded->model;
  const vision::RegistrationTarget& target = loaded->target;

  session::RegistrationCaptureOptions capture;
  capture.directory = options.output;
  capture.frames_per_pose = options.frames;
  capture.velocity_scale = options.speed;
  capture.settle_s = options.settle_s;
  capture.seed = options.seed;
  capture.marker = loaded->marker;
  capture.target = target;
  if (options.poses.rfind("auto:", 0) == 0) {
    const std::string count = options.poses.substr(5);
    try {
      std::size_t used = 0;
      capture.auto_poses = std::stoi(count, &used);
      if (used != count.size()) throw std::invalid_argument(count);
    } catch (const std::exception&) {
      return fail("--poses '" + options.poses + "': expected auto:N with N a number");
    }
  } else {
    auto poses = session::load_capture_poses_file(options.poses, arm.dof());
    if (!poses) return fail("--poses: " + poses.error().message);
    capture.poses = std::move(*poses);
  }
  if (Status s = capture.validate(); !s) return fail(s.error().message);

  auto clients = connect(options);
  if (!clients) return fail(clients.error().message);
  net::RobotClient& robot = *clients->robot;
  net::VisionClient& vision = *clients->vision;

  auto result = session::capture_for_registration(arm, robot, vision, capture,
                                                  [&](const session::CaptureProgress& p) {
                                                    out << p.message << "\n" << std::flush;
                                                  });
  if (!result) return fail(result.error().message, 1);
  for (const std::string& note : result->notes) out << "note: " << note << "\n";
  // Where the target was seen in each eye, for the operator to judge the spread.
  auto detected = vision::detect_capture_targets(options.output, result->capture, target);
  if (detected) {
    const std::string coverage = options.output + "/coverage.png";
    const auto& camera = result->cameras.left;
    if (vision::write_png_file(coverage,
                               vision::coverage_image(*detected, camera.width, camera.height))) {
      out << "coverage: the " << (target.is_board() ? "board" : "marker") << " found at "
          << detected->left_found << " (left) and " << detected->right_found << " (right) of "
          << result->capture.poses.size() << " poses; " << coverage << "\n";
    }
  }
  out << "wrote " << options.output << "/capture.yaml (" << result->capture.poses.size()
      << " poses); register with: telear register --captures " << options.output << " --robot "
      << options.robot_spec().name_or_path << " -o registered.yaml\n";
  return 0;
}

}  // namespace telear::cli
