#include "apps/render_command.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <ostream>
#include <vector>

#include "apps/cli_parsing.hpp"
#include "telear/core/angles.hpp"
#include "telear/core/arm_body.hpp"
#include "telear/core/arm_body_pose.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/geometry/robot_assets.hpp"
#include "telear/render/arm_renderer.hpp"
#include "telear/render/egl_context.hpp"
#include "telear/render/image_io.hpp"
#include "telear/render/offscreen_target.hpp"
#include "telear/render/overlay.hpp"
#include "telear/render/scene_objects.hpp"
#include "telear/render/stereo_composer.hpp"
#include "telear/vision/camera_file.hpp"

namespace telear::cli {
namespace {

constexpr int kBadInput = 2;
constexpr int kGlFailure = 1;
constexpr double kStereoBaseline = 0.06;  // m, the seed's two cameras

struct Eye {
  std::string name;  // "left", "right" or "" (mono)
  vision::CameraModel camera;
};

struct Failure {
  std::string message;
};

std::vector<std::string> split_pair(const std::string& text) {
  const size_t comma = text.find(',');
  if (comma == std::string::npos) return {text};
  return {text.substr(0, comma), text.substr(comma + 1)};
}

Eigen::VectorXd joints_from_options(const core::RobotModel& model, const RenderOptions& options) {
  if (options.q.empty()) throw Failure{"--q is required (joint values or a named configuration)"};
  if (auto named = model.named_configuration(options.q)) return *named;
  auto values = parse_number_list(options.q, "--q", model.dof());
  if (!values) {
    throw Failure{values.error().message + " (robot '" + model.name() + "' has " +
                  std::to_string(model.dof()) + " joints)"};
  }
  Eigen::VectorXd q = to_vector(*values);
  if (options.degrees) {
    for (int i = 0; i < model.dof(); ++i) {
      if (model.joint(i).type == core::JointType::kRevolute)
        q[i] = core::radians_from_degrees(q[i]);
    }
  }
  return q;
}

// A camera that sees the whole arm at q: the bounding sphere of its frames (plus a margin
// for the body) fills the smaller field of view, seen from the front-right, above.
std::vector<Eye> default_eyes(const core::RobotModel& model, const Eigen::VectorXd& q, int width,
                              int height, bool stereo) {
  core::KinematicsData data(model);
  core::forward_kinematics(model, data, q);
  Eigen::AlignedBox3d box(Eigen::Vector3d::Zero());
  for (const Eigen::Isometry3d& T : data.T_base_link) box.extend(T.translation());
  box.extend(data.T_base_tool.translation());
  const Eigen::Vector3d centre = box.center();
  const double radius = 0.5 * box.diagonal().norm() + 0.25;
  const double vertical_fov = core::radians_from_degrees(45.0);
  const double horizontal_fov = 2.0 * std::atan(std::tan(vertical_fov / 2) * width / height);
  const double distance = radius / std::sin(0.5 * std::min(vertical_fov, horizontal_fov));
  const Eigen::Vector3d direction = Eigen::Vector3d(0.75, -0.6, 0.35).normalized();
  const vision::CameraModel middle = vision::look_at_camera(
      width, height, vertical_fov, centre + distance * direction, centre, Eigen::Vector3d::UnitZ());
  if (!stereo) return {{"", middle}};
  std::vector<Eye> eyes;
  for (const auto& [name, side] : {std::pair{"left", -0.5}, std::pair{"right", 0.5}}) {
    vision::CameraModel c = middle;
    // Move the optical centre along the camera's x axis: p_cam' = p_cam - (side * b, 0, 0).
    c.T_cam_base.pretranslate(Eigen::Vector3d(-side * kStereoBaseline, 0, 0));
    eyes.push_back({name, c});
  }
  return eyes;
}

std::vector<Eye> eyes_from_options(const RenderOptions& options, const core::RobotModel& model,
                                   const Eigen::VectorXd& q, int default_width,
                                   int default_height) {
  const std::string& eye = options.eye;
  if (!eye.empty() && eye != "left" && eye != "right" && eye != "both") {
    throw Failure{"--eye must be left, right or both, got '" + eye + "'"};
  }
  if (options.camera.empty()) {
    std::vector<Eye> eyes = default_eyes(model, q, default_width, default_height, eye == "both");
    if (eye == "right") eyes[0].name = "right";
    return eyes;
  }
  const std::vector<std::string> paths = split_pair(options.camera);
  Result<vision::CameraFile> file = paths.size() == 2
                                        ? vision::load_stereo_camera_files(paths[0], paths[1])
                                        : vision::load_camera_file(paths[0]);
  if (!file) throw Failure{file.error().message};
  auto posed = [&](const vision::CameraModel& c, bool has_pose, const std::string& name) {
    if (!has_pose) {
      throw Failure{"camera file '" + options.camera + "': " + (name.empty() ? "the" : name) +
                    " camera has no T_cam_base (register it to the robot first)"};
    }
    return Eye{name, c};
  };
  if (!file->is_stereo()) {
    if (eye == "right" || eye == "both") {
      throw Failure{"--eye " + eye + " needs a stereo camera file; '" + options.camera +
                    "' holds one camera"};
    }
    return {posed(file->left, file->left_has_pose, "")};
  }
  std::vector<Eye> eyes;
  if (eye != "right") eyes.push_back(posed(file->left, file->left_has_pose, "left"));
  if (eye != "left") eyes.push_back(posed(*file->right, file->right_has_pose, "right"));
  return eyes;
}

std::vector<core::Image> backgrounds_from_options(const RenderOptions& options) {
  if (options.background.empty()) return {};
  std::vector<core::Image> images;
  for (const std::string& path : split_pair(options.background)) {
    if (path.empty())
      throw Failure{"--background: empty file name in '" + options.background + "'"};
    Result<core::Image> image = render::read_image(path, 3);
    if (!image) throw Failure{image.error().message};
    images.push_back(std::move(image.value()));
  }
  return images;
}

std::string eye_output_path(const std::string& output, const std::string& eye) {
  const size_t dot = output.rfind('.');
  const size_t slash = output.rfind('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) {
    return output + "_" + eye;
  }
  return output.substr(0, dot) + "_" + eye + output.substr(dot);
}

void check_options(const RenderOptions& options) {
  if (options.output.empty()) throw Failure{"-o is required (the PNG to write)"};
  if (options.segments != 0 &&
      (options.segments < core::kMinCylinderSegments || options.segments > 512)) {
    throw Failure{"--segments must be in [3, 512], got " + std::to_string(options.segments)};
  }
  if (!(options.alpha > 0.0 && options.alpha <= 1.0)) {
    char value[32];
    std::snprintf(value, sizeof value, "%g", options.alpha);
    throw Failure{std::string("--alpha must be in (0, 1], got ") + value};
  }
  if (options.gripper && !(std::isfinite(*options.gripper) && *options.gripper >= 0.0)) {
    throw Failure{"--gripper must be a finite opening >= 0 m"};
  }
  if (options.width < 16 || options.width > 8192 || options.height < 16 || options.height > 8192) {
    throw Failure{"--width and --height must be in [16, 8192]"};
  }
}

}  // namespace

int run_render(const RenderOptions& options, std::ostream& out, std::ostream& err) {
  const std::string prefix = "telear render: ";
  // [SECTION] inputs: everything untrusted is checked before any GL work.
  core::RobotModelPtr model;
  Eigen::VectorXd q;
  std::vector<Eye> eyes;
  std::vector<core::Image> backgrounds;
  render::StereoLayout layout = render::StereoLayout::kSideBySide;
  core::BodyDescription description;
  try {
    check_options(options);
    auto geometry = options.geometry_options();
    if (!geometry) throw Failure{geometry.error().message};
    auto loaded = geometry::load_robot_assets(options.robot_spec(), *geometry);
    if (!loaded) throw Failure{loaded.error().message};
    for (const std::string& warning : loaded->warnings)
      err << prefix << "warning: " << warning << "\n";
    model = loaded->model();
    description = std::move(loaded->body);
    q = joints_from_options(*model, options);
    backgrounds = backgrounds_from_options(options);
    const int default_width = backgrounds.empty() ? options.width : backgrounds[0].width;
    const int default_height = backgrounds.empty() ? options.height : backgrounds[0].height;
    eyes = eyes_from_options(options, *model, q, default_width, default_height);
    if (backgrounds.size() > eyes.size()) {
      throw Failure{"--background gives two images but only one eye is drawn"};
    }
    for (size_t i = 0; i < eyes.size() && !backgrounds.empty(); ++i) {
      const core::Image& image = backgrounds[std::min(i, backgrounds.size() - 1)];
      const vision::CameraModel& c = eyes[i].camera;
      if (image.width != c.width || image.height != c.height) {
        throw Failure{"--background image is " + std::to_string(image.width) + "x" +
                      std::to_string(image.height) + " but the " +
                      (eyes[i].name.empty() ? "" : eyes[i].name + " ") + "camera's image is " +
                      std::to_string(c.width) + "x" + std::to_string(c.height)};
      }
    }
    if (eyes.size() == 2) {
      auto parsed = render::parse_stereo_layout(options.stereo);
      if (!parsed) throw Failure{"--stereo: " + parsed.error().message};
      layout = *parsed;
      if (layout != render::StereoLayout::kSeparate &&
          (eyes[0].camera.width != eyes[1].camera.width ||
           eyes[0].camera.height != eyes[1].camera.height)) {
        throw Failure{
            "the left and right cameras have different image sizes; use --stereo "
            "separate"};
      }
    }
  } catch (const Failure& f) {
    err << prefix << f.message << "\n";
    return kBadInput;
  }

  // [SECTION] drawing
  auto context = render::create_headless_context();
  if (!context) {
    err << prefix << "no OpenGL context: " << context.error().message << "\n";
    return kGlFailure;
  }
  const core::ArmBody body =
      core::build_arm_body(description, {.segments_override = options.segments});
  core::ArmBodyPose pose(*model, body);
  pose.set_configuration(q);
  if (options.gripper) pose.set_gripper_opening(static_cast<float>(*options.gripper));
  auto arm = render::ArmRenderer::create(body);
  if (!arm) {
    err << prefix << arm.error().message << "\n";
    return kGlFailure;
  }
  arm->update(pose);
  std::vector<render::SceneObject> objects;
  if (options.floor) objects.push_back(render::make_floor(3.0f, 12, 0.0f));
  if (options.cube) objects.push_back(render::make_cube(0.2f, {0.55f, -0.35f, 0.1f}));
  std::optional<render::MeshSetRenderer> scene;
  if (!objects.empty()) {
    auto s = render::create_scene_renderer(objects);
    if (!s) {
      err << prefix << s.error().message << "\n";
      return kGlFailure;
    }
    scene = std::move(s.value());
  }
  render::DrawOptions draw;
  draw.style = options.wireframe ? render::DrawOptions::Style::kWireframe
                                 : render::DrawOptions::Style::kSolid;
  draw.alpha = static_cast<float>(options.alpha);
  const render::SceneDrawer draw_scene = [&](const Eigen::Matrix4f& projection,
                                             const Eigen::Matrix4f& view) {
    if (scene) scene->draw(projection, view, {});
    if (!options.no_arm) arm->draw(projection, view, draw);
  };

  std::vector<render::OffscreenTarget> targets;
  const render::OverlayOptions overlay_options{
      .mode = options.undistort ? render::OverlayMode::kUndistorted : render::OverlayMode::kRaw,
      .clear_colour = Eigen::Vector3f(0.16f, 0.18f, 0.22f)};
  for (size_t i = 0; i < eyes.size(); ++i) {
    auto overlay = render::Overlay::create(eyes[i].camera, overlay_options);
    auto target = render::OffscreenTarget::create(eyes[i].camera.width, eyes[i].camera.height);
    if (!overlay || !target) {
      err << prefix << (overlay ? target.error().message : overlay.error().message) << "\n";
      return kGlFailure;
    }
    if (!backgrounds.empty()) {
      overlay->upload_frame(backgrounds[std::min(i, backgrounds.size() - 1)].pixels.data(),
                            render::ChannelOrder::kRgb);
    }
    overlay->render(*target, draw_scene);
    targets.push_back(std::move(target.value()));
  }

  // [SECTION] output
  std::vector<std::pair<std::string, core::Image>> images;
  if (eyes.size() == 1) {
    images.emplace_back(options.output, targets[0].read_rgb());
  } else if (layout == render::StereoLayout::kSeparate) {
    images.emplace_back(eye_output_path(options.output, "left"), targets[0].read_rgb());
    images.emplace_back(eye_output_path(options.output, "right"), targets[1].read_rgb());
  } else {
    auto composer = render::StereoComposer::create();
    const render::ComposedSize size =
        render::composed_size(layout, targets[0].width(), targets[0].height());
    auto composed = render::OffscreenTarget::create(size.width, size.height);
    if (!composer || !composed) {
      err << prefix << (composer ? composed.error().message : composer.error().message) << "\n";
      return kGlFailure;
    }
    composer->compose(layout, targets[0].colour_texture(), targets[1].colour_texture(), *composed);
    images.emplace_back(options.output, composed->read_rgb());
  }
  for (const auto& [path, image] : images) {
    if (Status written = render::write_png(path, image); !written) {
      err << prefix << written.error().message << "\n";
      return kBadInput;
    }
    out << "wrote " << path << " (" << image.width << "x" << image.height;
    if (eyes.size() == 2 && layout != render::StereoLayout::kSeparate) {
      out << ", stereo " << render::stereo_layout_name(layout);
    }
    out << ", " << (options.undistort ? "undistorted" : "raw") << " overlay"
        << (options.camera.empty() ? ", default view" : "") << ")\n";
  }
  return 0;
}

}  // namespace telear::cli
