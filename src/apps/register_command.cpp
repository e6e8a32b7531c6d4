#include "apps/register_command.hpp"

#include <cstdio>
#include <iomanip>
#include <ostream>
#include <sstream>

#include "telear/core/robot_loader.hpp"
#include "telear/vision/calibration_file.hpp"
#include "telear/vision/camera_file.hpp"
#include "telear/vision/observations_file.hpp"
#include "telear/vision/registration.hpp"

namespace telear::cli {
namespace {

constexpr const char* kCommand = "telear register: ";

int fail(std::ostream& err, const std::string& message, int code = 2) {
  err << kCommand << message << "\n";
  return code;
}

// An OpenCV FileStorage matrix entry (rows x cols, row-major data), as cv::FileStorage
// writes it, so OpenCV programs and load_stereo_geometry() read the appended keys.
std::string matrix_entry(const std::string& key, int rows, int cols, const double* data) {
  std::ostringstream s;
  s << std::setprecision(17);
  s << key << ": !!opencv-matrix\n   rows: " << rows << "\n   cols: " << cols
    << "\n   dt: d\n   data: [ ";
  for (int i = 0; i < rows * cols; ++i) s << data[i] << (i + 1 == rows * cols ? " ]\n" : ", ");
  return s.str();
}

std::string residual_line(const char* label, const vision::EyeResiduals& r) {
  char line[160];
  std::snprintf(line, sizeof line, "  %-22s %6d points  RMS %8.4f px  max %8.4f px\n", label,
                r.observations, r.rms_px, r.max_px);
  return line;
}

}  // namespace

int run_register(const RegisterOptions& options, std::ostream& out, std::ostream& err) {
  if (options.rig.empty()) return fail(err, "--rig: give the stereo camera file to register");
  if (options.observations.empty())
    return fail(err, "--observations: give the observations file (telear sim observations)");
  if (options.output.empty())
    return fail(err, "-o: give the camera file to write, e.g. -o stereo_registered.yaml");
  if (options.max_iterations < 1)
    return fail(
        err, "--max-iterations " + std::to_string(options.max_iterations) + " must be at least 1");
  if (Status s = vision::check_output_path(options.output, "-o"); !s)
    return fail(err, s.error().message);

  auto cameras = vision::load_camera_file(options.rig);
  if (!cameras) return fail(err, "--rig: " + cameras.error().message);
  if (!cameras->is_stereo()) {
    return fail(err, "--rig '" + options.rig +
                         "' is a mono camera file; registration needs a stereo pair (the "
                         "output of `telear calibrate --left ... --right ...`)");
  }
  Eigen::Isometry3d T_right_left = Eigen::Isometry3d::Identity();
  if (auto geometry = vision::load_stereo_geometry(options.rig)) {
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) T_right_left.linear()(r, c) = geometry->R(r, c);
      T_right_left.translation()(r) = geometry->T(r);
    }
  } else if (cameras->left_has_pose && cameras->right_has_pose) {
    T_right_left = vision::right_from_left(cameras->left.T_cam_base, cameras->right->T_cam_base);
  } else {
    return fail(err, "--rig: " + geometry.error().message +
                         ", and the file has no T_cam_base for both eyes either");
  }

  auto model = core::load_robot(options.robot);
  if (!model) return fail(err, "--robot: " + model.error().message);
  auto observations = vision::load_observations_file(options.observations);
  if (!observations) return fail(err, "--observations: " + observations.error().message);

  vision::RegistrationOptions registration_options;
  registration_options.max_iterations = options.max_iterations;
  auto result = vision::register_stereo(**model, cameras->left, *cameras->right, T_right_left,
                                        *observations, registration_options);
  if (!result) {
    return fail(err, "observations '" + options.observations + "': " + result.error().message);
  }

  vision::StereoCameraModel registered{cameras->left, *cameras->right};
  registered.left.T_cam_base = result->T_left_base;
  registered.right.T_cam_base = result->T_right_base;
  // The pair's geometry as R, T (X_R = R X_L + T), row-major.
  const Eigen::Matrix<double, 3, 3, Eigen::RowMajor> R = T_right_left.linear();
  const Eigen::Vector3d T = T_right_left.translation();
  std::string text = vision::opencv_stereo_camera_yaml(registered);
  text += "# Stereo geometry the registration held fixed: X_R = R X_L + T (metres).\n";
  text += matrix_entry("R", 3, 3, R.data());
  text += matrix_entry("T", 3, 1, T.data());
  if (Status s = vision::write_files_atomically({{options.output, text}}); !s) {
    return fail(err, s.error().message, 1);
  }

  out << "registered " << options.rig << " to " << options.robot << " from "
      << observations->configurations.size() << " configurations (" << result->configurations_used
      << " distinct) of " << observations->point_in_flange.size() << " point(s) each\n";
  for (const std::string& note : result->notes) out << "  note: " << note << "\n";
  out << "residuals after the PnP start:\n"
      << residual_line("left", result->initial_left)
      << residual_line("right", result->initial_right) << "residuals after refinement ("
      << result->iterations << " Levenberg-Marquardt iterations):\n"
      << residual_line("left", result->left) << residual_line("right", result->right);
  const Eigen::Vector3d c_left = result->T_left_base.inverse().translation();
  const Eigen::Vector3d c_right = result->T_right_base.inverse().translation();
  char line[200];
  std::snprintf(line, sizeof line,
                "camera centres in the base frame (m): left [%.4f, %.4f, %.4f], right "
                "[%.4f, %.4f, %.4f]\n",
                c_left.x(), c_left.y(), c_left.z(), c_right.x(), c_right.y(), c_right.z());
  out << line << "wrote " << options.output << "\n";
  return 0;
}

}  // namespace telear::cli
