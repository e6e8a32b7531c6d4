#pragma once
// The arm at one configuration, drawn headless through calibrated cameras -- or a default
// view of the whole arm -- optionally on a video frame per eye, mono or stereo: what
// `telear render` writes as PNG (docs/cameras.md, docs/cli.md). The overlay is the operator's
// (overlay.hpp: raw frame with the arm warped into it, or undistorted), so a snapshot shows
// exactly what the AR view would.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "telear/core/arm_body.hpp"
#include "telear/core/arm_body_pose.hpp"
#include "telear/core/image.hpp"
#include "telear/core/result.hpp"
#include "telear/core/robot_model.hpp"
#include "telear/render/draw_options.hpp"
#include "telear/render/stereo_composer.hpp"
#include "telear/vision/camera_model.hpp"

namespace telear::render {

struct SnapshotEye {
  std::string name;  // "left", "right", or "" (mono)
  vision::CameraModel camera;
};

// A camera that sees the whole arm at q: the bounding sphere of its frames (plus 0.25 m for
// the body) fills the smaller field of view (45 deg vertical), seen from the front-right,
// above. With `stereo`, two eyes the seed's 6 cm apart along the camera's x axis.
std::vector<SnapshotEye> whole_arm_view(const core::RobotModel& model, const Eigen::VectorXd& q,
                                        int width, int height, bool stereo);

// The eyes to draw, as `telear render --camera C --eye E` names them. `camera` empty: the
// whole-arm view (two eyes for "both"; "right" names the single eye right); else a camera file
// (mono or stereo) or "left.yaml,right.yaml", whose cameras must be registered (T_cam_base).
// `eye`: "", "left", "right" or "both" ("": every camera of the file). Errors name the option
// and the file: "eye both needs a stereo camera file; 'c.yaml' holds one camera".
Result<std::vector<SnapshotEye>> snapshot_eyes(const std::string& camera, const std::string& eye,
                                               const core::RobotModel& model,
                                               const Eigen::VectorXd& q, int default_width,
                                               int default_height);

// The video frames behind the arm: "" none, "f.png" for every eye, "left.png,right.png" one per
// eye (PNG or JPEG, read as RGB). Errors name the file.
Result<std::vector<core::Image>> read_snapshot_backgrounds(const std::string& background);

// Where one eye of a `--stereo separate` snapshot goes: "out.png" -> "out_left.png".
std::string snapshot_eye_path(const std::string& output, const std::string& eye);

// What must hold before any GL work: each background (one for every eye, or one per eye) has
// its eye's image size, and a composed stereo layout has two eyes of one size. Errors name
// the sizes ("background image is 320x240 but the left camera's image is 640x480").
Status check_snapshot_inputs(const std::vector<SnapshotEye>& eyes,
                             const std::vector<core::Image>& backgrounds, StereoLayout layout);

struct SnapshotOptions {
  DrawOptions draw;        // solid or wire-frame, alpha < 1 for a ghost
  bool undistort = false;  // the undistorted overlay mode (default: raw)
  bool draw_arm = true;    // false: the scene alone (e.g. to make a background)
  bool floor = false;      // a checkered floor at z = 0
  bool cube = false;       // the seed's cube on the floor in front of the arm
  StereoLayout layout = StereoLayout::kSideBySide;  // two eyes
};

// The images: one for a single eye or a composed stereo layout, one per eye with kSeparate.
// Needs a current GL context; inputs must pass check_snapshot_inputs. Errors are GL failures.
Result<std::vector<core::Image>> draw_arm_snapshot(const core::ArmBody& body,
                                                   core::ArmBodyPose& pose,
                                                   const std::vector<SnapshotEye>& eyes,
                                                   const std::vector<core::Image>& backgrounds,
                                                   const SnapshotOptions& options);

}  // namespace telear::render
