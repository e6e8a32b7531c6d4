#include "telear/sim/scene_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "telear/core/kinematics.hpp"
#include "telear/core/seeded_random.hpp"
#include "telear/render/camera_projection.hpp"

namespace telear::sim {
namespace {

// A floor of square tiles whose grey varies a little from tile to tile (a fixed generator),
// like worn concrete slabs: texture for the eye, but no high-contrast checkerboard that a
// chessboard detector could mistake for the target.
core::Mesh make_tiled_floor(double size_m, int tiles) {
  core::Mesh mesh;
  std::mt19937 generator(12345u);
  std::uniform_real_distribution<float> shade(0.42f, 0.52f);
  const Eigen::Vector3f n(0.f, 0.f, 1.f);
  const double tile = size_m / tiles;
  const double gap = 0.004;  // a darker joint between tiles
  for (int j = 0; j < tiles; ++j) {
    for (int i = 0; i < tiles; ++i) {
      const float g = shade(generator);
      const Eigen::Vector3f colour(g * 1.02f, g, g * 0.96f);
      const float x0 = static_cast<float>(-size_m / 2 + i * tile + gap);
      const float y0 = static_cast<float>(-size_m / 2 + j * tile + gap);
      const float x1 = static_cast<float>(-size_m / 2 + (i + 1) * tile - gap);
      const float y1 = static_cast<float>(-size_m / 2 + (j + 1) * tile - gap);
      const std::uint32_t a = mesh.add_vertex({x0, y0, 0.f}, n, colour);
      const std::uint32_t b = mesh.add_vertex({x1, y0, 0.f}, n, colour);
      const std::uint32_t c = mesh.add_vertex({x1, y1, 0.f}, n, colour);
      const std::uint32_t d = mesh.add_vertex({x0, y1, 0.f}, n, colour);
      mesh.triangles.insert(mesh.triangles.end(), {a, b, c, a, c, d});
    }
  }
  // The joints: one slightly lower, darker plane under the tiles.
  const Eigen::Vector3f joint(0.3f, 0.3f, 0.3f);
  const float h = static_cast<float>(size_m / 2);
  const std::uint32_t a = mesh.add_vertex({-h, -h, -0.001f}, n, joint);
  const std::uint32_t b = mesh.add_vertex({h, -h, -0.001f}, n, joint);
  const std::uint32_t c = mesh.add_vertex({h, h, -0.001f}, n, joint);
  const std::uint32_t d = mesh.add_vertex({-h, h, -0.001f}, n, joint);
  mesh.triangles.insert(mesh.triangles.end(), {a, b, c, a, c, d});
  return mesh;
}

}  // namespace

vision::CameraModel supersampled_camera(const vision::CameraModel& camera, int factor) {
  vision::CameraModel scaled = camera;
  const double s = factor;
  scaled.width = camera.width * factor;
  scaled.height = camera.height * factor;
  scaled.fx = camera.fx * s;
  scaled.fy = camera.fy * s;
  scaled.cx = s * (camera.cx + 0.5) - 0.5;
  scaled.cy = s * (camera.cy + 0.5) - 0.5;
  return scaled;
}

core::Image downsample_box(const core::Image& image, int factor) {
  const int width = image.width / factor;
  const int height = image.height / factor;
  core::Image out(width, height, 3);
  const int channels = image.channels;
  const int area = factor * factor;
  std::vector<int> sums(static_cast<std::size_t>(width) * 3);
  for (int y = 0; y < height; ++y) {
    std::fill(sums.begin(), sums.end(), 0);
    for (int dy = 0; dy < factor; ++dy) {
      const std::uint8_t* row = image.row(y * factor + dy);
      for (int x = 0; x < width; ++x) {
        const std::uint8_t* p = row + static_cast<std::size_t>(x) * factor * channels;
        for (int dx = 0; dx < factor; ++dx, p += channels) {
          sums[3 * x] += p[0];
          sums[3 * x + 1] += p[1];
          sums[3 * x + 2] += p[2];
        }
      }
    }
    std::uint8_t* out_row = out.row(y);
    for (int k = 0; k < width * 3; ++k) {
      out_row[k] = static_cast<std::uint8_t>((sums[k] + area / 2) / area);
    }
  }
  return out;
}

std::uint64_t noise_seed(std::uint64_t seed, std::uint64_t frame, Eye eye) {
  return core::mix_seed(core::mix_seed(core::mix_seed(seed) ^ frame) ^
                        (eye == Eye::kLeft ? 1u : 2u));
}

void add_sensor_noise(core::Image& image, double sigma, std::uint64_t seed) {
  if (sigma <= 0.0) return;
  std::mt19937_64 generator(seed);
  // Uniform in (0, 1] from 53 random bits, then Box-Muller: two normals per pair.
  const auto uniform = [&generator] {
    return (static_cast<double>(generator() >> 11) + 1.0) * (1.0 / 9007199254740992.0);
  };
  const std::size_t n = image.pixels.size();
  for (std::size_t i = 0; i < n; i += 2) {
    const double radius = sigma * std::sqrt(-2.0 * std::log(uniform()));
    const double angle = 2.0 * std::numbers::pi * uniform();
    const double noise[2] = {radius * std::cos(angle), radius * std::sin(angle)};
    for (std::size_t k = 0; k < 2 && i + k < n; ++k) {
      const double value = std::round(image.pixels[i + k] + noise[k]);
      image.pixels[i + k] = static_cast<std::uint8_t>(std::clamp(value, 0.0, 255.0));
    }
  }
}

Result<SceneRenderer> SceneRenderer::create(const StereoRig& rig, const core::RobotModel& model,
                                            const core::BodyDescription& body,
                                            const SceneOptions& options) {
  if (options.supersample < 1 || options.supersample > 8) {
    return Error{"supersampling factor " + std::to_string(options.supersample) +
                 " is outside 1..8"};
  }
  if (!(options.noise_sigma >= 0.0) || options.noise_sigma > 100.0) {
    return Error{"sensor noise must be between 0 and 100 grey levels"};
  }
  SceneRenderer scene;
  scene.rig_ = rig;
  scene.options_ = options;
  scene.model_ = &model;
  scene.body_ = core::build_arm_body(body);
  scene.pose_.emplace(model, scene.body_);
  auto arm = render::ArmRenderer::create(scene.body_);
  if (!arm) return arm.error();
  scene.arm_ = std::move(*arm);

  // The room's floor, then the workspace's fixed objects, then its graspable object (a part
  // of its own, moved by set_object_pose), each mesh in its own frame.
  std::vector<core::Mesh> meshes;
  std::vector<Eigen::Isometry3d> poses;
  meshes.push_back(make_tiled_floor(8.0, 20));
  poses.push_back(Eigen::Isometry3d::Identity());
  const core::WorkspaceObject* graspable = rig.workspace.first_graspable();
  for (const core::WorkspaceObject& object : rig.workspace.objects) {
    if (&object == graspable) continue;
    meshes.push_back(core::workspace_object_mesh(object));
    poses.push_back(object.T_base_object);
  }
  if (graspable) {
    meshes.push_back(core::workspace_object_mesh(*graspable));
    poses.push_back(graspable->T_base_object);
    scene.object_part_ = static_cast<int>(meshes.size()) - 1;
  }
  std::vector<const core::Mesh*> parts;
  for (const core::Mesh& mesh : meshes) parts.push_back(&mesh);
  auto environment = render::MeshSetRenderer::create(parts);
  if (!environment) return environment.error();
  scene.environment_ = std::move(*environment);
  for (std::size_t i = 0; i < poses.size(); ++i) {
    scene.environment_.set_matrix(static_cast<int>(i), poses[i].matrix().cast<float>());
  }
  if (graspable) scene.set_object_pose(graspable->T_base_object);

  if (options.show_marker) {
    // The marker asked for, else the rig's, else the robot's own marker file.
    Result<core::MarkerMount> mount = options.marker ? Result<core::MarkerMount>(*options.marker)
                                      : rig.marker   ? Result<core::MarkerMount>(*rig.marker)
                                                     : core::marker_mount_for(model);
    if (!mount) return mount.error();
    const std::string spec = options.target.empty() ? rig.target : options.target;
    if (spec.empty()) {
      auto marker = make_aruco_marker(*mount);
      if (!marker) return marker.error();
      scene.marker_ = std::move(*marker);
    } else {
      auto target = vision::parse_registration_target(spec);
      if (!target) return target.error();
      scene.flange_target_ = make_flange_target(*target, mount->T_flange_marker);
    }
    auto parts = render::MeshSetRenderer::create(
        {scene.marker_ ? &scene.marker_->mesh : &scene.flange_target_->mesh});
    if (!parts) return parts.error();
    scene.marker_parts_ = std::move(*parts);
  }

  render::OverlayOptions overlay_options;
  overlay_options.mode = render::OverlayMode::kRaw;
  overlay_options.clear_colour = options.background;
  overlay_options.samples = options.multisample;
  for (int eye = 0; eye < 2; ++eye) {
    const vision::CameraModel camera =
        supersampled_camera(rig.camera(eye == 0 ? Eye::kLeft : Eye::kRight), options.supersample);
    auto overlay = render::Overlay::create(camera, overlay_options);
    if (!overlay) return overlay.error();
    scene.overlay_[eye] = std::move(*overlay);
    auto target = render::OffscreenTarget::create(camera.width, camera.height);
    if (!target) return target.error();
    scene.high_res_[eye] = std::move(*target);
  }
  return scene;
}

Eigen::Isometry3d SceneRenderer::T_base_flange() const {
  return pose_->kinematics().T_base_link.back();
}

std::array<Eigen::Vector3d, 4> SceneRenderer::marker_corners_base() const {
  std::array<Eigen::Vector3d, 4> corners{};
  if (!marker_) return corners;
  const Eigen::Isometry3d T = T_base_flange();
  for (int k = 0; k < 4; ++k) corners[k] = T * marker_->corners_flange[k];
  return corners;
}

Eigen::Isometry3d SceneRenderer::T_base_grip() const {
  // A URDF arm's tip is its tool centre point between the fingers (robot file `tip:`).
  if (!body_.gripper) return T_base_flange();
  const auto& gripper = *body_.gripper;
  Eigen::Isometry3d T = pose_->kinematics().T_base_link[gripper.link];
  T.translation() = T * gripper.centre.cast<double>();
  return T;
}

double SceneRenderer::gripper_opening_m(double opening) const {
  return body_.gripper_opening_m(opening);
}

void SceneRenderer::set_configuration(const Eigen::VectorXd& q) {
  if (q_.size() == q.size() && q_ == q) return;
  q_ = q;
  pose_->set_configuration(q);
  ++scene_version_;
}

void SceneRenderer::set_gripper_opening(float opening_m) {
  if (opening_m == opening_m_) return;
  opening_m_ = opening_m;
  pose_->set_gripper_opening(opening_m);
  ++scene_version_;
}

void SceneRenderer::clear_target() {
  has_target_ = false;
  ++scene_version_;
}

void SceneRenderer::set_object_pose(const Eigen::Isometry3d& T_base_object) {
  if (T_base_object.matrix() != T_base_object_.matrix()) ++scene_version_;
  T_base_object_ = T_base_object;
  if (object_part_ >= 0)
    environment_.set_matrix(object_part_, T_base_object.matrix().cast<float>());
}

Status SceneRenderer::set_target(const CalibrationTarget& target,
                                 const Eigen::Isometry3d& T_base_target) {
  auto parts = render::MeshSetRenderer::create({&target.mesh});
  if (!parts) return parts.error();
  target_ = std::move(*parts);
  target_.set_matrix(0, T_base_target.matrix().cast<float>());
  T_base_target_ = T_base_target;
  has_target_ = true;
  ++scene_version_;
  return Status::Ok();
}

core::Image SceneRenderer::render_clean(Eye eye) {
  const int index = eye == Eye::kLeft ? 0 : 1;
  if (drawn_version_[index] == scene_version_) return drawn_[index];
  arm_.update(*pose_);
  if (marker_ || flange_target_) {
    marker_parts_.set_matrix(0, T_base_flange().matrix().cast<float>());
  }
  render::DrawOptions solid;
  solid.lighting = options_.lighting;
  render::DrawOptions flat = solid;
  flat.cull_back_faces = false;  // the targets and the floor are open, one-sided meshes
  overlay_[index].render(
      high_res_[index], [&](const Eigen::Matrix4f& projection, const Eigen::Matrix4f& T_view_base) {
        if (options_.show_environment) environment_.draw(projection, T_view_base, flat);
        if (options_.show_robot) {
          arm_.draw(projection, T_view_base, solid);
          if (marker_ || flange_target_) marker_parts_.draw(projection, T_view_base, flat);
        }
        if (has_target_) target_.draw(projection, T_view_base, flat);
      });
  const core::Image high = high_res_[index].read_rgba();
  drawn_[index] = downsample_box(high, options_.supersample);
  drawn_version_[index] = scene_version_;
  ++draw_count_;
  return drawn_[index];
}

core::Image SceneRenderer::render(Eye eye, std::uint64_t frame) {
  core::Image image = render_clean(eye);
  const std::uint64_t seed = noise_seed(options_.seed, frame, eye);
  if (!options_.fast_noise || options_.noise_sigma <= 0.0) {
    add_sensor_noise(image, options_.noise_sigma, seed);
    return image;
  }
  constexpr std::size_t kTableSize = std::size_t{1} << 20;
  if (noise_table_.empty()) {
    // The table is the exact generator's output on a mid-grey image, minus the grey.
    core::Image grey(static_cast<int>(kTableSize), 1, 1);
    std::fill(grey.pixels.begin(), grey.pixels.end(), std::uint8_t{128});
    add_sensor_noise(grey, options_.noise_sigma, options_.seed);
    noise_table_.resize(kTableSize);
    for (std::size_t i = 0; i < kTableSize; ++i) {
      noise_table_[i] = static_cast<std::int8_t>(static_cast<int>(grey.pixels[i]) - 128);
    }
  }
  const std::size_t offset = static_cast<std::size_t>(seed) & (kTableSize - 1);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    const int value = image.pixels[i] + noise_table_[(offset + i) & (kTableSize - 1)];
    image.pixels[i] = static_cast<std::uint8_t>(std::clamp(value, 0, 255));
  }
  return image;
}

}  // namespace telear::sim
