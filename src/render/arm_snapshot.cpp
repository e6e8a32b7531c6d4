#include "telear/render/arm_snapshot.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "telear/core/angles.hpp"
#include "telear/core/image_size.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/render/arm_renderer.hpp"
#include "telear/render/image_io.hpp"
#include "telear/render/offscreen_target.hpp"
#include "telear/render/overlay.hpp"
#include "telear/render/scene_objects.hpp"
#include "telear/vision/camera_file.hpp"

namespace telear::render {
namespace {

constexpr double kStereoBaseline = 0.06;  // m, the seed's two cameras

// "a.yaml,b.yaml" -> {"a.yaml", "b.yaml"}; without a comma, the text alone.
std::vector<std::string> split_pair(const std::string& text) {
  const size_t comma = text.find(',');
  if (comma == std::string::npos) return {text};
  return {text.substr(0, comma), text.substr(comma + 1)};
}

}  // namespace

std::vector<SnapshotEye> whole_arm_view(const core::RobotModel& model, const Eigen::VectorXd& q,
                                        int width, int height, bool stereo) {
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
  std::vector<SnapshotEye> eyes;
  for (const auto& [name, side] : {std::pair{"left", -0.5}, std::pair{"right", 0.5}}) {
    vision::CameraModel c = middle;
    // Move the optical centre along the camera's x axis: p_cam' = p_cam - (side * b, 0, 0).
    c.T_cam_base.pretranslate(Eigen::Vector3d(-side * kStereoBaseline, 0, 0));
    eyes.push_back({name, c});
  }
  return eyes;
}

Result<std::vector<SnapshotEye>> snapshot_eyes(const std::string& camera, const std::string& eye,
                                               const core::RobotModel& model,
                                               const Eigen::VectorXd& q, int default_width,
                                               int default_height) {
  if (!eye.empty() && eye != "left" && eye != "right" && eye != "both") {
    return Error{"eye must be left, right or both, got '" + eye + "'"};
  }
  if (camera.empty()) {
    auto eyes = whole_arm_view(model, q, default_width, default_height, eye == "both");
    if (eye == "right") eyes[0].name = "right";
    return eyes;
  }
  const std::vector<std::string> paths = split_pair(camera);
  Result<vision::CameraFile> file = paths.size() == 2
                                        ? vision::load_stereo_camera_files(paths[0], paths[1])
                                        : vision::load_camera_file(paths[0]);
  if (!file) return file.error();
  std::vector<SnapshotEye> eyes;
  const auto add = [&](const vision::CameraModel& c, bool has_pose, const std::string& name) {
    if (!has_pose) {
      return Status(Error{"camera file '" + camera + "': " + (name.empty() ? "the" : name) +
                          " camera has no T_cam_base (register it to the robot first)"});
    }
    eyes.push_back({name, c});
    return Status::Ok();
  };
  if (!file->is_stereo()) {
    if (eye == "right" || eye == "both") {
      return Error{"eye " + eye + " needs a stereo camera file; '" + camera + "' holds one camera"};
    }
    if (Status s = add(file->left, file->left_has_pose, ""); !s) return s.error();
    return eyes;
  }
  if (eye != "right") {
    if (Status s = add(file->left, file->left_has_pose, "left"); !s) return s.error();
  }
  if (eye != "left") {
    if (Status s = add(*file->right, file->right_has_pose, "right"); !s) return s.error();
  }
  return eyes;
}

Result<std::vector<core::Image>> read_snapshot_backgrounds(const std::string& background) {
  std::vector<core::Image> images;
  if (background.empty()) return images;
  for (const std::string& path : split_pair(background)) {
    if (path.empty()) return Error{"background: empty file name in '" + background + "'"};
    Result<core::Image> image = read_image(path, 3);
    if (!image) return image.error();
    images.push_back(std::move(image.value()));
  }
  return images;
}

std::string snapshot_eye_path(const std::string& output, const std::string& eye) {
  const size_t dot = output.rfind('.');
  const size_t slash = output.rfind('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) {
    return output + "_" + eye;
  }
  return output.substr(0, dot) + "_" + eye + output.substr(dot);
}

Status check_snapshot_inputs(const std::vector<SnapshotEye>& eyes,
                             const std::vector<core::Image>& backgrounds, StereoLayout layout) {
  if (backgrounds.size() > eyes.size()) {
    return Error{"background gives two images but only one eye is drawn"};
  }
  for (size_t i = 0; i < eyes.size() && !backgrounds.empty(); ++i) {
    const core::Image& image = backgrounds[std::min(i, backgrounds.size() - 1)];
    const vision::CameraModel& c = eyes[i].camera;
    if (image.width != c.width || image.height != c.height) {
      return Error{"background image is " +
                   core::to_string(core::ImageSize{image.width, image.height}) + " but the " +
                   (eyes[i].name.empty() ? "" : eyes[i].name + " ") + "camera's image is " +
                   core::to_string(core::ImageSize{c.width, c.height})};
    }
  }
  if (eyes.size() == 2 && layout != StereoLayout::kSeparate &&
      (eyes[0].camera.width != eyes[1].camera.width ||
       eyes[0].camera.height != eyes[1].camera.height)) {
    return Error{
        "the left and right cameras have different image sizes; use the separate stereo "
        "layout"};
  }
  return Status::Ok();
}

Result<std::vector<core::Image>> draw_arm_snapshot(const core::ArmBody& body,
                                                   core::ArmBodyPose& pose,
                                                   const std::vector<SnapshotEye>& eyes,
                                                   const std::vector<core::Image>& backgrounds,
                                                   const SnapshotOptions& options) {
  auto arm = ArmRenderer::create(body);
  if (!arm) return arm.error();
  arm->update(pose);
  std::vector<SceneObject> objects;
  if (options.floor) objects.push_back(make_floor(3.0f, 12, 0.0f));
  if (options.cube) objects.push_back(make_cube(0.2f, {0.55f, -0.35f, 0.1f}));
  std::optional<MeshSetRenderer> scene;
  if (!objects.empty()) {
    auto s = create_scene_renderer(objects);
    if (!s) return s.error();
    scene = std::move(s.value());
  }
  const SceneDrawer draw_scene = [&](const Eigen::Matrix4f& projection,
                                     const Eigen::Matrix4f& view) {
    if (scene) scene->draw(projection, view, {});
    if (options.draw_arm) arm->draw(projection, view, options.draw);
  };

  std::vector<OffscreenTarget> targets;
  const OverlayOptions overlay_options{
      .mode = options.undistort ? OverlayMode::kUndistorted : OverlayMode::kRaw,
      .clear_colour = Eigen::Vector3f(0.16f, 0.18f, 0.22f)};
  for (size_t i = 0; i < eyes.size(); ++i) {
    auto overlay = Overlay::create(eyes[i].camera, overlay_options);
    if (!overlay) return overlay.error();
    auto target = OffscreenTarget::create(eyes[i].camera.width, eyes[i].camera.height);
    if (!target) return target.error();
    if (!backgrounds.empty()) {
      overlay->upload_frame(backgrounds[std::min(i, backgrounds.size() - 1)].pixels.data(),
                            ChannelOrder::kRgb);
    }
    overlay->render(*target, draw_scene);
    targets.push_back(std::move(target.value()));
  }

  std::vector<core::Image> images;
  if (eyes.size() == 1 || options.layout == StereoLayout::kSeparate) {
    for (const OffscreenTarget& target : targets) images.push_back(target.read_rgb());
    return images;
  }
  auto composer = StereoComposer::create();
  if (!composer) return composer.error();
  const ComposedSize size = composed_size(options.layout, targets[0].width(), targets[0].height());
  auto composed = OffscreenTarget::create(size.width, size.height);
  if (!composed) return composed.error();
  composer->compose(options.layout, targets[0].colour_texture(), targets[1].colour_texture(),
                    *composed);
  images.push_back(composed->read_rgb());
  return images;
}

}  // namespace telear::render
