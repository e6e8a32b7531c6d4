#pragma once
// The "real" scene as the simulated stereo rig's TRUE cameras see it: a tiled floor, the
// rig's workspace (include/telear/core/workspace.hpp: a table, the box to pick), the robot
// with its real body (not the ghost's), an optional calibration target and the ArUco marker
// on the gripper (include/telear/core/marker_mount.hpp), lit by the renderer's ambient +
// directional light. Each eye is rendered through the renderer's raw (distorted) overlay pipeline
// with the eye's true camera, so the image carries the true lens distortion; then Gaussian sensor
// noise is added.
//
// Anti-aliasing by supersampling. A camera scaled by S has the same lens and the pixel grid
// refined S times:  fx' = S fx, fy' = S fy, c' = S (c + 0.5) - 0.5, size' = S size, the same
// alpha_c and kc (distortion acts on normalized coordinates). High-res pixel (i', j') covers
// [i' - 0.5, i' + 0.5) there, i.e. [(i' + 0.5) / S - 1, ...) ... ; the S x S block
// i' = S i .. S i + S - 1 covers exactly pixel i's square [i - 0.5, i + 0.5). Averaging each
// block therefore gives each pixel its area-weighted coverage (S^2 samples): edges and corners
// land where the true camera puts them, without the half-pixel bias of point sampling.
//
// Noise: per pixel and channel N(0, noise_sigma) grey levels, from a std::mt19937_64 seeded
// by (seed, frame, eye), turned into normals by Box-Muller (not std::normal_distribution,
// whose algorithm differs between standard libraries): the same seed and frame give the same
// image, bit for bit.
//
// Needs a current GL context (render::create_headless_context) for create() and render().

#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <string>

#include "telear/core/arm_body.hpp"
#include "telear/core/arm_body_pose.hpp"
#include "telear/core/image.hpp"
#include "telear/core/marker_mount.hpp"
#include "telear/core/robot_model.hpp"
#include "telear/render/arm_renderer.hpp"
#include "telear/render/draw_options.hpp"
#include "telear/render/mesh_set_renderer.hpp"
#include "telear/render/offscreen_target.hpp"
#include "telear/render/overlay.hpp"
#include "telear/sim/calibration_targets.hpp"
#include "telear/sim/flange_target.hpp"
#include "telear/sim/stereo_rig.hpp"

namespace telear::sim {

struct SceneOptions {
  int supersample = 4;  // S above, 1..8
  // Multisampling (MSAA) of the S-times grid, 1..the driver's limit (4 on llvmpipe): the
  // cheap way to the same area coverage at edges -- each pixel's colour is shaded once, its
  // coverage counted at `multisample` points -- where S = 1 would point-sample (a straight
  // edge a staircase of whole pixels, which moves a detected marker corner by up to 0.5 px).
  int multisample = 1;
  double noise_sigma = 1.0;  // grey levels (0..255 scale), 0 = none
  std::uint64_t seed = 1;
  // Video: the noise comes from a table of 2^20 N(0, sigma) values (rounded) drawn once,
  // added from a (seed, frame, eye)-random offset: ~20x cheaper than drawing every pixel's
  // noise, the same distribution per pixel, but frames share shifted copies of one pattern.
  // Stills (calibration views, observations) keep the exact per-pixel draw.
  bool fast_noise = false;
  bool show_robot = true;
  bool show_environment = true;  // the floor and the rig's workspace
  bool show_marker = true;       // the registration marker on the flange
  // The marker to draw; nullopt: the rig's marker file, else the robot's (marker_mount_for).
  std::optional<core::MarkerMount> marker;
  // A registration target to draw instead, where that marker mount sits (a spec of
  // telear/vision/registration_target.hpp); empty: the rig's `target:`, else the marker.
  std::string target;
  render::Lighting lighting;
  Eigen::Vector3f background{0.55f, 0.58f, 0.62f};  // walls (where nothing is drawn)
};

class SceneRenderer {
 public:
  SceneRenderer() = default;
  // The model must outlive the renderer. `body` is the real arm's look (the rig's body file).
  // Errors: invalid options, GL failures.
  static Result<SceneRenderer> create(const StereoRig& rig, const core::RobotModel& model,
                                      const core::BodyDescription& body,
                                      const SceneOptions& options = {});

  const StereoRig& rig() const { return rig_; }
  const SceneOptions& options() const { return options_; }

  void set_configuration(const Eigen::VectorXd& q);
  void set_gripper_opening(float opening_m);
  // Pose of the last link (flange / tool frame) in the base frame, at the current joints.
  Eigen::Isometry3d T_base_flange() const;
  // The gripper's centre frame (between the fingers, the gripper link's axes) in the base
  // frame at the current joints; the flange when the body has no gripper.
  Eigen::Isometry3d T_base_grip() const;
  // Finger gap (m) of a gripper opening 0..1 (0 without a gripper).
  double gripper_opening_m(double opening) const;
  // The mount's ArUco marker, when it is what the flange carries.
  const std::optional<ArucoMarker>& marker() const { return marker_; }
  // The target the flange carries instead (SceneOptions::target or the rig's), if any.
  const std::optional<FlangeTarget>& flange_target() const { return flange_target_; }
  // Where the box is (base frame, its centre): on the table at first; a grasp moves it
  // (telear/sim/grasp_model.hpp).
  void set_object_pose(const Eigen::Isometry3d& T_base_object);
  const Eigen::Isometry3d& object_pose() const { return T_base_object_; }
  // Marker corners in the base frame at the current joints.
  std::array<Eigen::Vector3d, 4> marker_corners_base() const;

  // Places a calibration target (its mesh uploaded once per call) or removes it.
  Status set_target(const CalibrationTarget& target, const Eigen::Isometry3d& T_base_target);
  void clear_target();

  // The eye's image without noise (RGB, camera size, top row first) and with the noise of
  // (options.seed, frame, eye). A scene that has not changed since the eye's last image (the
  // arm at rest, a camera watching it) is not drawn again: its last clean image is reused,
  // and only the noise is new. (GL draws the same scene to the same pixels, so this is the
  // image a new draw would give; on a CPU renderer the draw is ~95 % of a frame's cost.)
  core::Image render_clean(Eye eye);
  core::Image render(Eye eye, std::uint64_t frame);
  // How many times an eye was drawn by GL (not reused).
  std::uint64_t draw_count() const { return draw_count_; }

 private:
  StereoRig rig_;
  SceneOptions options_;
  const core::RobotModel* model_ = nullptr;
  core::ArmBody body_;
  std::optional<core::ArmBodyPose> pose_;  // optional: ArmBodyPose has no empty state
  render::ArmRenderer arm_;
  render::MeshSetRenderer environment_;
  render::MeshSetRenderer target_;
  render::MeshSetRenderer marker_parts_;
  std::optional<ArucoMarker> marker_;
  std::optional<FlangeTarget> flange_target_;
  Eigen::Isometry3d T_base_target_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d T_base_object_ = Eigen::Isometry3d::Identity();
  int object_part_ = -1;  // the graspable object's part in environment_, -1: none
  bool has_target_ = false;
  render::Overlay overlay_[2];
  render::OffscreenTarget high_res_[2];
  std::vector<std::int8_t> noise_table_;  // fast_noise: 2^20 values
  // What the last draw showed: the scene's version (bumped by every setter that changes what
  // is drawn), the joints and opening it compares against, and each eye's clean image.
  std::uint64_t scene_version_ = 1;
  Eigen::VectorXd q_;
  float opening_m_ = -1.0f;
  std::uint64_t drawn_version_[2] = {0, 0};
  core::Image drawn_[2];
  std::uint64_t draw_count_ = 0;
};

// The camera with its pixel grid refined `factor` times (see the header comment).
vision::CameraModel supersampled_camera(const vision::CameraModel& camera, int factor);

// Averages factor x factor blocks of an RGB(A) image into RGB.
core::Image downsample_box(const core::Image& image, int factor);

// Adds N(0, sigma) grey levels to every byte, rounding and clamping; seeded generator.
void add_sensor_noise(core::Image& image, double sigma, std::uint64_t seed);

// The generator seed of (seed, frame, eye) (a splitmix64 mix, stable across platforms).
std::uint64_t noise_seed(std::uint64_t seed, std::uint64_t frame, Eye eye);

}  // namespace telear::sim
