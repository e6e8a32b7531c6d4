#include "apps/register_command.hpp"

#include <algorithm>
#include <optional>
#include <ostream>

#include "apps/command_failure.hpp"
#include "telear/core/marker_mount.hpp"
#include "telear/core/robot_loader.hpp"
#include "telear/vision/calibration_file.hpp"
#include "telear/vision/camera_file.hpp"
#include "telear/vision/capture_registration.hpp"
#include "telear/vision/observations_file.hpp"
#include "telear/vision/registered_camera_file.hpp"
#include "telear/vision/registration.hpp"
#include "telear/vision/registration_target.hpp"

namespace telear::cli {
namespace {

// --captures: the marker detected in a capture folder, hand-eye registration.
int run_register_captures(const RegisterOptions& options, std::ostream& out, std::ostream& err) {
  const CommandFailure fail{err, "telear register"};
  auto model = core::load_robot(options.robot_spec());
  if (!model) return fail("--robot: " + model.error().message);
  auto marker = core::marker_mount_for(**model);
  if (!marker) return fail("--robot: " + marker.error().message);
  std::optional<vision::RegistrationTarget> target;
  if (!options.target.empty()) {
    auto parsed = vision::parse_registration_target(options.target);
    if (!parsed) return fail("--target: " + parsed.error().message);
    target = *parsed;
  }
  vision::HandEyeOptions hand_eye;
  hand_eye.max_iterations = std::max(options.max_iterations, 1);
  auto registration =
      vision::register_captures(**model, options.captures, options.rig, *marker, hand_eye, target);
  if (!registration) return fail(registration.error().message);
  const std::string text =
      vision::registered_camera_yaml(registration->registered, registration->T_right_left);
  if (Status s = vision::write_files_atomically({{options.output, text}}); !s) {
    return fail(s.error().message, 1);
  }
  out << "registered " << options.robot_spec().name_or_path << " from " << options.captures << "\n"
      << vision::capture_registration_report(*registration) << "wrote " << options.output << "\n";
  return 0;
}

}  // namespace

int run_register(const RegisterOptions& options, std::ostream& out, std::ostream& err) {
  const CommandFailure fail{err, "telear register"};
  if (!options.captures.empty() && !options.observations.empty())
    return fail("--captures and --observations: give one of them");
  if (!options.target.empty() && options.captures.empty())
    return fail("--target: only with --captures (an observations file holds points, not images)");
  if (options.output.empty())
    return fail("-o: give the camera file to write, e.g. -o stereo_registered.yaml");
  if (!options.captures.empty()) {
    if (Status s = vision::check_output_path(options.output, "-o"); !s)
      return fail(s.error().message);
    return run_register_captures(options, out, err);
  }
  if (options.rig.empty()) return fail("--rig: give the stereo camera file to register");
  if (options.observations.empty())
    return fail(
        "--observations or --captures: give the observations file (telear sim "
        "observations) or a capture folder (telear capture)");
  if (options.max_iterations < 1)
    return fail("--max-iterations " + std::to_string(options.max_iterations) +
                " must be at least 1");
  if (Status s = vision::check_output_path(options.output, "-o"); !s)
    return fail(s.error().message);

  auto cameras = vision::load_camera_file(options.rig);
  if (!cameras) return fail("--rig: " + cameras.error().message);
  if (!cameras->is_stereo()) {
    return fail("--rig '" + options.rig +
                "' is a mono camera file; registration needs a stereo pair (the "
                "output of `telear calibrate --left ... --right ...`)");
  }
  auto T_right_left = vision::stereo_pair_geometry(options.rig, *cameras);
  if (!T_right_left) return fail("--rig: " + T_right_left.error().message);

  auto model = core::load_robot(options.robot_spec());
  if (!model) return fail("--robot: " + model.error().message);
  auto observations = vision::load_observations_file(options.observations);
  if (!observations) return fail("--observations: " + observations.error().message);

  vision::RegistrationOptions registration_options;
  registration_options.max_iterations = options.max_iterations;
  auto result = vision::register_stereo(**model, cameras->left, *cameras->right, *T_right_left,
                                        *observations, registration_options);
  if (!result) {
    return fail("observations '" + options.observations + "': " + result.error().message);
  }

  vision::StereoCameraModel registered{cameras->left, *cameras->right};
  registered.left.T_cam_base = result->T_left_base;
  registered.right.T_cam_base = result->T_right_base;
  const std::string text = vision::registered_camera_yaml(registered, *T_right_left);
  if (Status s = vision::write_files_atomically({{options.output, text}}); !s) {
    return fail(s.error().message, 1);
  }

  out << "registered " << options.rig << " to " << options.robot << " from "
      << observations->configurations.size() << " configurations (" << result->configurations_used
      << " distinct) of " << observations->point_in_flange.size() << " point(s) each\n";
  out << vision::registration_summary(*result);
  out << "wrote " << options.output << "\n";
  return 0;
}

}  // namespace telear::cli
