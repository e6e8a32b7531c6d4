#pragma once
// The operator's stereo view: what the demo records and the console shows, per eye and
// composed.
//
// AR mode (fresh video): the eye's video frame is the background, drawn through the
// calibrated camera (raw or undistorted, telear/render/overlay.hpp), and over it
//   - the ghost: the commanded / rehearsed pose, tinted and translucent (ghost_alpha), and
//   - the reported ghost: where the robot *reported* it is now, fainter (reported_alpha), so
//     the operator sees how far the video lags the robot (the video should show the arm
//     where the reported ghost is, minus the video's age).
// Ghost links in contact (ArViewInput::ghost_highlight_frames) are drawn red.
// VR mode (late or stopped video): no video; the whole scene is drawn virtually — the
// workspace objects, the arm opaque at its reported pose, the ghost over it.
// In both modes, when the video and the robot's state are late, the predicted arm: where the arm
// is *now* (session::ArmPredictor's phantom robot), a wire-frame in its own colour (magenta),
// so that it reads apart from the ghost (blue) and the reported arm (yellow).
// Optionally (show_capture_arm), in AR over the video: the arm as it was reported at the frame's
// capture time, a white wire-frame that must sit on the arm the video shows (where it does not,
// the registration or the clocks are off; the predicted arm is ahead of it by the delay).
//
// A coloured frame around each eye says what the operator is looking at: green = live AR,
// amber = VR, red = stale (the video shown, if any, is old: it is never passed off as live).
//
// Needs a current GL context for create() and render(); every GL object lives as long as the
// view. One view renders ~0.5 ms per eye on llvmpipe at 640x480 besides the upload.

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "telear/core/arm_body.hpp"
#include "telear/core/arm_body_pose.hpp"
#include "telear/core/image.hpp"
#include "telear/core/result.hpp"
#include "telear/core/robot_model.hpp"
#include "telear/render/arm_renderer.hpp"
#include "telear/render/draw_options.hpp"
#include "telear/render/mesh_set_renderer.hpp"
#include "telear/render/offscreen_target.hpp"
#include "telear/render/overlay.hpp"
#include "telear/render/scene_objects.hpp"
#include "telear/render/stereo_composer.hpp"
#include "telear/vision/camera_model.hpp"

namespace telear::render {

enum class ViewMode { kAr, kVr };

enum class ViewStatus { kLive, kVirtual, kStale };

struct ArViewOptions {
  StereoLayout layout = StereoLayout::kSideBySide;  // kSeparate: no composition
  OverlayMode overlay_mode = OverlayMode::kRaw;
  DrawOptions::Style ghost_style = DrawOptions::Style::kSolid;
  float ghost_alpha = 0.55f;
  Eigen::Vector3f ghost_colour{0.2f, 0.75f, 1.0f};
  Eigen::Vector3f contact_colour{0.95f, 0.08f, 0.08f};  // highlighted ghost links
  bool show_reported_ghost = true;
  float reported_alpha = 0.25f;
  Eigen::Vector3f reported_colour{1.0f, 0.85f, 0.2f};
  bool show_predicted = true;
  Eigen::Vector3f predicted_colour{0.95f, 0.2f, 0.9f};
  bool show_capture_arm = false;  // the arm at the frame's capture (AR only)
  Eigen::Vector3f capture_colour{0.95f, 0.95f, 0.95f};
  int status_border_px = 4;  // 0: no frame around the eyes
  Eigen::Vector3f vr_background{0.16f, 0.18f, 0.22f};
};

struct ArViewInput {
  ViewMode mode = ViewMode::kAr;
  bool stale = false;  // the frame is older than the display's threshold (or stopped)
  const core::Image* left = nullptr;  // RGB8 video frames at the cameras' sizes; null: none
  const core::Image* right = nullptr;
  // Or the frames as decoded JPEG planes (net::VisionClientOptions::decode_planes), converted
  // on the GPU; used where left / right are null.
  const core::YCbCrImage* left_planes = nullptr;
  const core::YCbCrImage* right_planes = nullptr;
  Eigen::VectorXd ghost_q;     // the ghost (commanded / rehearsed pose)
  double ghost_gripper = 1.0;  // 0 closed .. 1 open
  // Chain frames (0 = base .. n) whose ghost parts are drawn in the highlight colour
  // (ArViewOptions::contact_colour): the links in contact at the ghost's pose. A frame's
  // parts are the link and what rides on it (the gripper's fingers ride on frame n).
  std::vector<int> ghost_highlight_frames;
  Eigen::VectorXd reported_q;  // empty: not drawn
  double reported_gripper = 1.0;
  Eigen::VectorXd predicted_q;  // the arm predicted now; empty: not drawn
  double predicted_gripper = 1.0;
  Eigen::VectorXd capture_q;  // the arm at the video frame's capture; empty: not drawn
  double capture_gripper = 1.0;
};

class ArView {
 public:
  ArView() = default;
  // `cameras` is the estimated calibration (with the registered T_cam_base): it draws the
  // ghost where the real arm appears. `objects` are drawn in VR mode (a floor, the box).
  static Result<ArView> create(const core::RobotModel& model, const core::ArmBody& body,
                               const vision::StereoCameraModel& cameras,
                               const std::vector<SceneObject>& objects,
                               const ArViewOptions& options = {});

  const ArViewOptions& options() const { return options_; }
  void set_options(const ArViewOptions& options) { options_ = options; }

  // Renders both eyes and (unless kSeparate) the composition. Frames must match the cameras'
  // sizes (a mismatched frame is not drawn: VR background instead, and status kStale).
  void render(const ArViewInput& input);
  ViewStatus status() const { return status_; }

  const OffscreenTarget& eye(int index) const { return eyes_[index]; }
  // The composed image's target (the left eye for kSeparate).
  const OffscreenTarget& composed() const;
  core::Image read_composed_rgb() const { return composed().read_rgb(); }

 private:
  ArView(const core::RobotModel& model, const core::ArmBody& body);
  void draw_eye(int index, const ArViewInput& input, bool video_ok);
  bool draws_predicted(const ArViewInput& input) const {
    return options_.show_predicted && input.predicted_q.size() == model_->dof();
  }
  bool draws_capture_arm(const ArViewInput& input) const {
    return options_.show_capture_arm && input.capture_q.size() == model_->dof();
  }
  void draw_status_border(const OffscreenTarget& target) const;

  const core::RobotModel* model_ = nullptr;
  core::ArmBody body_;
  std::unique_ptr<core::ArmBodyPose> ghost_pose_, reported_pose_, predicted_pose_, capture_pose_;
  ArmRenderer ghost_, reported_, predicted_, capture_;
  std::optional<MeshSetRenderer> objects_;
  vision::StereoCameraModel cameras_;
  Overlay overlays_[2];
  OffscreenTarget eyes_[2];
  StereoComposer composer_;
  OffscreenTarget composed_;
  ArViewOptions options_;
  ViewStatus status_ = ViewStatus::kVirtual;
};

}  // namespace telear::render
