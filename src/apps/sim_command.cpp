#include "apps/sim_command.hpp"

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

namespace telear::cli {
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

int run_sim_capture(const SimCaptureOptions& options, std::ostream& out, std::ostream& err) {
  if (options.views < 1 || options.views > 100) {
    err << "error: --views " << options.views << " is outside 1..100\n";
    return 2;
  }
  if (options.output.empty()) {
    err << "error: -o DIR is required (the directory to write the images and truth.yaml to)\n";
    return 2;
  }
  auto pattern = vision::parse_calibration_pattern(options.pattern);
  if (!pattern) {
    err << "error: --pattern: " << pattern.error().message << "\n";
    return 2;
  }
  auto rig = sim::load_stereo_rig(options.rig);
  if (!rig) {
    err << "error: " << rig.error().message << "\n";
    return 1;
  }
  auto model = core::load_robot(rig->robot);
  if (!model) {
    err << "error: rig '" << options.rig << "': robot: " << model.error().message << "\n";
    return 1;
  }
  auto body = rig->body_file.empty() ? core::body_description_for(**model)
                                     : load_body_yaml_file(rig->body_file, **model);
  if (!body) {
    err << "error: " << body.error().message << "\n";
    return 1;
  }
  const sim::CalibrationTarget target = sim::make_calibration_target(*pattern);
  auto poses = sim::calibration_target_poses(rig->cameras, rig->T_base_rig, target, options.views,
                                             options.seed);
  if (!poses) {
    err << "error: " << poses.error().message << "\n";
    return 1;
  }

  std::error_code ec;
  fs::create_directories(options.output, ec);
  if (ec || !fs::is_directory(options.output)) {
    err << "error: cannot create the output directory '" << options.output
        << "': " << (ec ? ec.message() : "not a directory") << "\n";
    return 1;
  }

  auto context = render::create_headless_context();
  if (!context) {
    err << "error: " << context.error().message << "\n";
    return 1;
  }
  sim::SceneOptions scene_options;
  scene_options.seed = options.seed;
  scene_options.noise_sigma = options.noise;
  scene_options.supersample = options.supersample;
  scene_options.show_robot = !options.no_scene;
  scene_options.show_environment = !options.no_scene;
  auto scene = sim::SceneRenderer::create(*rig, **model, *body, scene_options);
  if (!scene) {
    err << "error: " << scene.error().message << "\n";
    return 1;
  }
  if (auto qn = (*model)->named_configuration("qn")) scene->set_configuration(*qn);

  std::ostringstream views_yaml;
  views_yaml << std::setprecision(17);
  for (int view = 0; view < options.views; ++view) {
    const Eigen::Isometry3d& T_base_target = (*poses)[static_cast<std::size_t>(view)];
    if (auto placed = scene->set_target(target, T_base_target); !placed) {
      err << "error: " << placed.error().message << "\n";
      return 1;
    }
    const std::string left_name = view_name("left", view);
    const std::string right_name = view_name("right", view);
    for (const auto& [eye, name] :
         {std::pair{sim::Eye::kLeft, left_name}, std::pair{sim::Eye::kRight, right_name}}) {
      const core::Image image = scene->render(eye, static_cast<std::uint64_t>(view));
      if (auto written = render::write_png((fs::path(options.output) / name).string(), image);
          !written) {
        err << "error: " << written.error().message << "\n";
        return 1;
      }
    }
    const Eigen::Isometry3d T_left_target = rig->cameras.left.T_cam_base * T_base_target;
    views_yaml << "   -\n"
               << "      left_image: " << left_name << "\n"
               << "      right_image: " << right_name << "\n"
               << "      T_base_target: " << matrix_yaml(T_base_target.matrix(), "         ")
               << "      T_left_target: " << matrix_yaml(T_left_target.matrix(), "         ");
    out << "view " << (view + 1) << "/" << options.views << ": " << left_name << ", " << right_name
        << "\n"
        << std::flush;
  }

  std::ostringstream truth;
  truth << std::setprecision(17);
  truth << vision::opencv_stereo_camera_yaml(rig->cameras);
  truth << "# Ground truth of the simulated capture (docs/simulation.md): the TRUE cameras\n"
        << "# above, the target's pose per view (p_base = T_base_target p_target, target frame\n"
        << "# of telear/vision/calibration_pattern.hpp), sensor noise in grey levels.\n"
        << "rig: \"" << rig->name << "\"\n"
        << "baseline_m: " << rig->baseline_m << "\n"
        << "T_base_rig: " << matrix_yaml(rig->T_base_rig.matrix(), "   ") << "pattern: \""
        << pattern->spec() << "\"\n"
        << "seed: " << options.seed << "\n"
        << "noise_sigma_grey: " << options.noise << "\n"
        << "supersample: " << options.supersample << "\n"
        << "views:\n"
        << views_yaml.str();
  const fs::path truth_path = fs::path(options.output) / "truth.yaml";
  const fs::path temporary = fs::path(options.output) / ".truth.yaml.part";
  {
    std::ofstream file(temporary);
    file << truth.str();
    if (!file) {
      err << "error: cannot write '" << truth_path.string() << "'\n";
      fs::remove(temporary, ec);
      return 1;
    }
  }
  fs::rename(temporary, truth_path, ec);
  if (ec) {
    err << "error: cannot write '" << truth_path.string() << "': " << ec.message() << "\n";
    return 1;
  }
  out << "wrote " << options.views << " stereo pairs and " << truth_path.string() << "\n";
  return 0;
}

}  // namespace telear::cli
