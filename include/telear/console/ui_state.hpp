#pragma once
// The console's own state: only how things are shown and the operator's step sizes. Everything
// about the robot, the ghost and the plan lives in the Session; the console reads it each frame.

#include <optional>
#include <string>

#include "telear/core/motion_command.hpp"
#include "telear/render/ar_view.hpp"

namespace telear::console {

// How the stereo pair is shown in the view panel.
enum class ViewLayout {
  kSideBySide,
  kTopBottom,
  kAnaglyph,
  kLeftEye,
  kRightEye,
  kSeparate,  // both eyes as two images
  kPageFlip,  // quad-buffer stereo where the window has it (else side by side)
};

// "sbs", "tb", "anaglyph", "left", "right", "separate", "page-flip".
const char* layout_name(ViewLayout layout);
std::optional<ViewLayout> parse_layout(const std::string& name);

enum class InputTarget { kGhost, kReal };

struct UiState;
// The view settings the operator chose (style, ghost opacity, the real arm shown, the predicted
// arm shown, raw or undistorted video) applied to the AR view's options: the console's view each
// frame, and replay's with a default UiState, so that both draw alike. The layout is not among them
// (it needs the view rebuilt).
render::ArViewOptions with_view_settings(render::ArViewOptions options, const UiState& ui);

struct UiState {
  // [SECTION] view
  ViewLayout layout = ViewLayout::kSideBySide;
  bool wireframe = false;
  int segments = 0;  // 0: the body file's own
  float ghost_opacity = 0.55f;
  bool show_reported = true;
  bool show_predicted = true;     // the predicted arm when the link is late (session::ArmPredictor)
  bool show_capture_arm = false;  // the arm at the frame's capture, over the video
  bool undistorted = false;
  bool body_dirty = false;  // segments changed: the view's arm body must be rebuilt
  bool page_flip_granted = false;
  std::string page_flip_message;

  // [SECTION] motion steps (UI units)
  float joint_step_deg = 2.0f;
  float cartesian_step_mm = 10.0f;
  float rotation_step_deg = 5.0f;
  core::MotionFrame frame = core::MotionFrame::kBase;
  InputTarget input_target = InputTarget::kGhost;

  // [SECTION] plan editing
  float waypoint_duration_s = 1.0f;
  int selected_waypoint = -1;
  char waypoint_label[64] = "";

  // [SECTION] real robot
  int named_index = 0;
  char typed_configuration[128] = "";  // degrees, comma separated

  // [SECTION] live plots (the series are the Session's: Session::live_series())
  bool show_plots = false;

  // [SECTION] registration capture (the capture itself is the Session's)
  bool show_registration = false;
  char capture_folder[256] = "captures";
  char capture_target[128] = "";  // a target spec; empty: the robot's marker

  // [SECTION] connection (editable; "Connect" rebuilds the session with them)
  char robot_address[128] = "";
  char vision_address[128] = "";
  char token[128] = "";
  bool reconnect_requested = false;
  bool embedded = false;  // the session runs against the embedded simulated servers

  // [SECTION] feedback and automation
  std::string validation_text;  // the last validation's summary
  // Its collision check in one line (first contact or clearance; empty: not checked).
  std::string validation_collision;
  bool validation_collision_free = true;
  std::string last_message;  // the result of the last action, shown in the status bar
  bool last_failed = false;
  std::string calibration_note;  // where the drawn calibration came from
  std::optional<std::string> screenshot_request;
  bool quit = false;
  double fps = 0.0;  // console frames per second
};

}  // namespace telear::console
