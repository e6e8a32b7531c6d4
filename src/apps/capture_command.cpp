#include "apps/capture_command.hpp"

#include <opencv2/imgcodecs.hpp>
#include <ostream>

#include "telear/core/marker_mount.hpp"
#include "telear/core/robot_loader.hpp"
#include "telear/net/bearer_auth.hpp"
#include "telear/session/registration_capture.hpp"
#include "telear/vision/capture_observations.hpp"

namespace telear::cli {
namespace {

constexpr const char* kCommand = "telear capture: ";

int fail(std::ostream& err, const std::string& message, int code = 2) {
  err << kCommand << message << "\n";
  return code;
}

}  // namespace

int run_capture(const CaptureOptions& options, std::ostream& out, std::ostream& err) {
  if (options.robot_server.empty()) return fail(err, "--robot: give the robot server HOST:PORT");
  if (options.vision_server.empty()) return fail(err, "--vision: give the vision server HOST:PORT");
  if (options.output.empty()) return fail(err, "-o: give the folder to write");
  auto model = core::load_robot(options.robot_spec());
  if (!model) return fail(err, "--arm: " + model.error().message);
  auto marker = core::marker_mount_for(**model);
  if (!marker) return fail(err, "marker: " + marker.error().message);

  session::RegistrationCaptureOptions capture;
  capture.directory = options.output;
  capture.frames_per_pose = options.frames;
  capture.velocity_scale = options.speed;
  capture.settle_s = options.settle_s;
  capture.seed = options.seed;
  capture.marker = *marker;
  if (options.poses.rfind("auto:", 0) == 0) {
    const std::string count = options.poses.substr(5);
    try {
      std::size_t used = 0;
      capture.auto_poses = std::stoi(count, &used);
      if (used != count.size()) throw std::invalid_argument(count);
    } catch (const std::exception&) {
      return fail(err, "--poses '" + options.poses + "': expected auto:N with N a number");
    }
  } else {
    auto poses = session::load_capture_poses_file(options.poses, (*model)->dof());
    if (!poses) return fail(err, "--poses: " + poses.error().message);
    capture.poses = std::move(*poses);
  }
  if (Status s = capture.validate(); !s) return fail(err, s.error().message);

  std::string token;
  if (!options.token_file.empty()) {
    auto t = net::load_token_file(options.token_file);
    if (!t) return fail(err, "--token-file: " + t.error().message);
    token = *t;
  }
  net::RobotClientOptions robot_options;
  robot_options.address = options.robot_server;
  robot_options.token = token;
  robot_options.client_name = "telear-capture";
  net::RobotClient robot(robot_options);
  robot.start();
  net::VisionClientOptions vision_options;
  vision_options.address = options.vision_server;
  vision_options.token = token;
  vision_options.client_name = "telear-capture";
  vision_options.jpeg_quality = 100;  // the least loss the stream offers
  net::VisionClient vision(vision_options);
  vision.start();

  auto result = session::capture_for_registration(**model, robot, vision, capture,
                                                  [&](const session::CaptureProgress& p) {
                                                    out << p.message << "\n" << std::flush;
                                                  });
  if (!result) return fail(err, result.error().message, 1);
  for (const std::string& note : result->notes) out << "note: " << note << "\n";
  // Where the marker was seen in each eye, for the operator to judge the spread.
  auto detected = vision::detect_capture_targets(options.output, result->capture, *marker);
  if (detected) {
    const std::string coverage = options.output + "/coverage.png";
    const auto& camera = result->cameras.left;
    if (cv::imwrite(coverage, vision::coverage_image(*detected, camera.width, camera.height))) {
      out << "coverage: the marker found at " << detected->left_found << " (left) and "
          << detected->right_found << " (right) of " << result->capture.poses.size() << " poses; "
          << coverage << "\n";
    }
  }
  out << "wrote " << options.output << "/capture.yaml (" << result->capture.poses.size()
      << " poses); register with: telear register --captures " << options.output << " --robot "
      << options.robot_spec().name_or_path << " -o registered.yaml\n";
  return 0;
}

}  // namespace telear::cli
