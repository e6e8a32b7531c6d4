#include "telear/sim/calibration_capture.hpp"

#include "telear/sim/rig_robot.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <system_error>

#include "telear/core/arm_body.hpp"
#include "telear/core/robot_loader.hpp"
#include "telear/render/egl_context.hpp"
#include "telear/render/image_io.hpp"
#include "telear/sim/calibration_targets.hpp"
#include "telear/sim/scene_renderer.hpp"
#include "telear/sim/stereo_rig.hpp"
#include "telear/vision/calibration_pattern.hpp"
#include "telear/vision/camera_file.hpp"

namespace telear::sim {
namespace {

namespace fs = std::filesystem;

std::string matrix_yaml(const Eigen::Matrix4d& m, const std::string& indent) {
  std::ostringstream s;
  s << std::setprecision(17);
  s << "!!opencv-matrix\n"
    << indent << "rows: 4\n"
    << indent << "cols: 4\n"
    << indent << "dt: d\n"
    << indent << "data: [ ";
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) s << m(r, c) << (r == 3 && c == 3 ? " ]\n" : ", ");
  }
  return s.str();
}

std::string view_name(const char* eye, int view) {
  char name[32];
  std::snprintf(name, sizeof(name), "%s_%02d.png", eye, view);
  return name;
}

}  // namespace

Status CalibrationCaptureOptions::validate() const {
  if (views < 1 || views > 100) {
    return Error{"views " + std::to_string(views) + " is outside 1..100"};
  }
  if (output_dir.empty()) {
    return Error{"output_dir is required (the directory to write the images and truth.yaml to)"};
  }
  if (!(noise_grey >= 0.0 && noise_grey <= 50.0)) {
    return Error{"noise_grey must be within 0..50 grey levels"};
  }
  if (supersample < 1 || supersample > 8) return Error{"supersample must be within 1..8"};
  return Status::Ok();
}

Result<CalibrationCapture> capture_calibration_views(const CalibrationCaptureOptions& options,
                                                     const CaptureProgress& progress) {
  if (Status s = options.validate(); !s) return s.error();
  auto pattern = vision::parse_calibration_pattern(options.pattern);
  if (!pattern) return Error{"pattern: " + pattern.error().message};
  auto rig = load_stereo_rig(options.rig_file);
  if (!rig) return rig.error();
  auto robot = load_rig_robot(*rig);
  if (!robot) return robot.error();
  const core::RobotModelPtr model = robot->model();
  const core::BodyDescription* body = &robot->body;
  const CalibrationTarget target = make_calibration_target(*pattern);
  auto poses =
      calibration_target_poses(rig->cameras, rig->T_base_rig, target, options.views, options.seed);
  if (!poses) return poses.error();

  std::error_code ec;
  fs::create_directories(options.output_dir, ec);
  if (ec || !fs::is_directory(options.output_dir)) {
    return Error{"cannot create the output directory '" + options.output_dir +
                 "': " + (ec ? ec.message() : "not a directory")};
  }

  auto context = render::create_headless_context();
  if (!context) return context.error();
  SceneOptions scene_options;
  scene_options.seed = options.seed;
  scene_options.noise_sigma = options.noise_grey;
  scene_options.supersample = options.supersample;
  scene_options.show_robot = options.show_scene;
  scene_options.show_environment = options.show_scene;
  scene_options.marker = robot->description.marker;
  auto scene = SceneRenderer::create(*rig, *model, *body, scene_options);
  if (!scene) return scene.error();
  // The arm folded out of the way of the calibration target: the PUMA's nominal pose qn, else
  // the arm's rest pose.
  scene->set_configuration(model->named_configuration("qn").value_or(rest_configuration(*model)));

  CalibrationCapture capture;
  std::ostringstream views_yaml;
  views_yaml << std::setprecision(17);
  for (int view = 0; view < options.views; ++view) {
    const Eigen::Isometry3d& T_base_target = (*poses)[static_cast<std::size_t>(view)];
    if (auto placed = scene->set_target(target, T_base_target); !placed) return placed.error();
    const std::string left_name = view_name("left", view);
    const std::string right_name = view_name("right", view);
    for (const auto& [eye, name] :
         {std::pair{Eye::kLeft, left_name}, std::pair{Eye::kRight, right_name}}) {
      const core::Image image = scene->render(eye, static_cast<std::uint64_t>(view));
      const std::string path = (fs::path(options.output_dir) / name).string();
      if (auto written = render::write_png(path, image); !written) return written.error();
      (eye == Eye::kLeft ? capture.left_images : capture.right_images).push_back(path);
    }
    const Eigen::Isometry3d T_left_target = rig->cameras.left.T_cam_base * T_base_target;
    views_yaml << "   -\n"
               << "      left_image: " << left_name << "\n"
               << "      right_image: " << right_name << "\n"
               << "      T_base_target: " << matrix_yaml(T_base_target.matrix(), "         ")
               << "      T_left_target: " << matrix_yaml(T_left_target.matrix(), "         ");
    if (progress) progress(view + 1, options.views, left_name, right_name);
  }

  std::ostringstream truth;
  truth << std::setprecision(17);
  truth << vision::opencv_stereo_camera_yaml(rig->cameras);
  truth << "# Ground truth of the simulated capture (docs/simulation.md): the TRUE cameras\n"
        << "# above, the target's pose per view (p_base = T_base_target p_target, target frame\n"
        << "# of include/telear/vision/calibration_pattern.hpp), sensor noise in grey levels.\n"
        << "rig: \"" << rig->name << "\"\n"
        << "baseline_m: " << rig->baseline_m << "\n"
        << "T_base_rig: " << matrix_yaml(rig->T_base_rig.matrix(), "   ") << "pattern: \""
        << pattern->spec() << "\"\n"
        << "seed: " << options.seed << "\n"
        << "noise_sigma_grey: " << options.noise_grey << "\n"
        << "supersample: " << options.supersample << "\n"
        << "views:\n"
        << views_yaml.str();
  const fs::path truth_path = fs::path(options.output_dir) / "truth.yaml";
  const fs::path temporary = fs::path(options.output_dir) / ".truth.yaml.part";
  {
    std::ofstream file(temporary);
    file << truth.str();
    if (!file) {
      fs::remove(temporary, ec);
      return Error{"cannot write '" + truth_path.string() + "'"};
    }
  }
  fs::rename(temporary, truth_path, ec);
  if (ec) return Error{"cannot write '" + truth_path.string() + "': " + ec.message()};
  capture.truth_file = truth_path.string();
  return capture;
}

}  // namespace telear::sim
