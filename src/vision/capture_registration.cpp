#include "telear/vision/capture_registration.hpp"

#include <filesystem>
#include <sstream>

#include "telear/core/angles.hpp"
#include "telear/core/number_format.hpp"
#include "telear/vision/camera_file.hpp"
#include "telear/vision/registered_camera_file.hpp"

#include "vision_text.hpp"

namespace telear::vision {
namespace {

std::string vector3(const Eigen::Vector3d& v, int decimals) {
  // Appended piece by piece: GCC 12 warns (-Wrestrict, a false positive) on "[" + string.
  std::string out = "[";
  out += fixed(v.x(), decimals);
  out += ", ";
  out += fixed(v.y(), decimals);
  out += ", ";
  out += fixed(v.z(), decimals);
  out += "]";
  return out;
}

std::string eye_line(const std::string& label, const EyeResiduals& r) {
  return "  " + label + ": " + std::to_string(r.observations) + " points, RMS " +
         fixed(r.rms_px, 3) + " px, max " + fixed(r.max_px, 3) + " px\n";
}

}  // namespace

Result<CaptureRegistration> register_captures(const core::RobotModel& model,
                                              const std::string& directory,
                                              const std::string& rig_file,
                                              const core::MarkerMount& marker,
                                              const HandEyeOptions& options,
                                              const std::optional<RegistrationTarget>& target) {
  CaptureRegistration out;
  auto capture = load_capture_folder(directory);
  if (!capture) return capture.error();
  out.capture = std::move(*capture);
  if (!out.capture.poses.empty() && out.capture.poses.front().q.size() != model.dof()) {
    return Error{"capture '" + directory + "' has " +
                 std::to_string(out.capture.poses.front().q.size()) +
                 " joint values per pose, but robot '" + model.name() + "' has " +
                 std::to_string(model.dof()) + " joints: give the robot it was captured with"};
  }
  out.camera_file = rig_file;
  if (out.camera_file.empty()) {
    if (out.capture.camera_file.empty()) {
      return Error{"capture '" + directory +
                   "' holds no camera file: give the stereo calibration (a camera file)"};
    }
    out.camera_file = (std::filesystem::path(directory) / out.capture.camera_file).string();
  }
  auto cameras = load_camera_file(out.camera_file);
  if (!cameras) return cameras.error();
  if (!cameras->is_stereo()) {
    return Error{"'" + out.camera_file +
                 "' is a mono camera file; registration needs a stereo pair (the left and right "
                 "cameras calibrated together)"};
  }
  auto T_right_left = stereo_pair_geometry(out.camera_file, *cameras);
  if (!T_right_left) return T_right_left.error();
  out.T_right_left = *T_right_left;

  RegistrationTarget chosen = registration_target_from_mount(marker);
  if (target) {
    chosen = *target;
  } else if (!out.capture.target.empty()) {
    auto recorded = parse_registration_target(out.capture.target);
    if (!recorded) {
      return Error{"capture '" + directory + "': " + recorded.error().message +
                   " (give the registration target)"};
    }
    chosen = *recorded;
  }
  auto detected = detect_capture_targets(directory, out.capture, chosen);
  if (!detected) return detected.error();
  out.detected = std::move(*detected);
  auto result = register_hand_eye(model, cameras->left, *cameras->right, out.T_right_left,
                                  out.detected.observations, options);
  if (!result) return Error{"capture '" + directory + "': " + result.error().message};
  out.result = std::move(*result);
  out.registered = {cameras->left, *cameras->right};
  out.registered.left.T_cam_base = out.result.T_left_base;
  out.registered.right.T_cam_base = out.result.T_right_base;
  return out;
}

std::string capture_registration_report(const CaptureRegistration& r) {
  std::ostringstream out;
  const HandEyeResult& h = r.result;
  out << "capture: " << r.capture.poses.size() << " poses; " << r.detected.target.description()
      << " (" << r.detected.target.spec() << ") found at " << r.detected.left_found
      << " (left) and " << r.detected.right_found << " (right); calibration " << r.camera_file
      << "\n";
  for (const std::string& note : r.detected.notes) out << "  note: " << note << "\n";
  for (const std::string& note : h.notes) out << "  note: " << note << "\n";
  out << "per pose (RMS over both eyes):\n";
  for (const ViewFit& v : h.views) {
    out << "  " << v.name << ": " << v.left_points << " + " << v.right_points << " points, RMS "
        << fixed(v.rms_px, 3) << " px" << (v.dropped ? "  DROPPED" : "") << "\n";
  }
  out << "bundle adjustment (" << h.views_used << " poses, " << h.iterations << " iterations):\n"
      << eye_line("left", h.left) << eye_line("right", h.right);
  out << "uncertainty (1 sigma): base " << fixed(h.base_sigma.position_mm, 3) << " mm, "
      << fixed(h.base_sigma.rotation_deg, 4) << " deg; target on the flange "
      << fixed(h.target_sigma.position_mm, 3) << " mm, " << fixed(h.target_sigma.rotation_deg, 4)
      << " deg\n";
  out << "target on the flange: xyz " << vector3(h.T_flange_target.translation(), 4) << " m\n";
  out << "camera centres in the base frame (m): left "
      << vector3(h.T_left_base.inverse().translation(), 4) << ", right "
      << vector3(h.T_right_base.inverse().translation(), 4) << "\n";
  for (const auto& [eye, b] : {std::pair{"left", &h.baseline_left}, {"right", &h.baseline_right}}) {
    if (!b->solved) continue;
    const Eigen::Isometry3d difference =
        b->T_cam_base * (eye == std::string("left") ? h.T_left_base : h.T_right_base).inverse();
    out << "baseline " << eye << " (OpenCV calibrateRobotWorldHandEye, Shah, " << b->views
        << " poses): RMS " << fixed(b->residuals.rms_px, 3) << " px, "
        << fixed(1000.0 * difference.translation().norm(), 2) << " mm and "
        << fixed(core::degrees_from_radians(Eigen::AngleAxisd(difference.linear()).angle()), 3)
        << " deg from the bundle adjustment\n";
  }
  return out.str();
}

}  // namespace telear::vision
