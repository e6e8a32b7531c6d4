#pragma once
// One operator action in the console: what a button, a key, a gamepad or a script line asks
// for. Every source builds a UiAction and hands it to apply_action() (console_actions.hpp),
// so a script replays exactly the code path of the buttons.
//
// Units inside are the library's: radians, metres, seconds; scripts and panels convert at
// their edge (degrees, millimetres). Joint and waypoint indices are 0-based here (scripts and
// panels show them from 1).

#include <Eigen/Core>
#include <string>

#include "telear/core/motion_command.hpp"

namespace telear::console {

enum class ActionKind {
  // connection
  kConnect,
  kDisconnect,
  kTakeControl,
  kReleaseControl,
  kEStop,
  kResetEStop,
  // ghost
  kGhostJoint,      // index = joint, value = delta (rad or m)
  kGhostCartesian,  // frame, dX (m), dM (rad)
  kGhostGripper,    // value = opening 0..1
  kGhostNamed,      // text = configuration name
  kGhostToReal,
  // real robot (the conventional mode)
  kRealJoint,       // index, value
  kRealCartesian,   // frame, dX, dM
  kRealGripper,     // value
  kRealInitialize,  // text = name, or q (rad) when text is empty
  // plan
  kPlanAdd,       // value = min duration (s), text = label
  kPlanDelete,    // index
  kPlanMove,      // index -> index2
  kPlanDuration,  // index, value (s)
  kPlanClear,
  kPlanSave,  // text = path
  kPlanLoad,  // text = path
  kPreviewPlay,
  kPreviewPause,
  kPreviewStop,
  kPreviewSeek,   // value = s
  kPreviewSpeed,  // value
  kValidate,
  kExecute,
  kCancel,
  // view
  kViewLayout,     // text = sbs | tb | anaglyph | left | right | separate | page-flip
  kViewStyle,      // text = solid | wire
  kViewSegments,   // index = segments (0: the body's own)
  kViewOpacity,    // value = ghost opacity (0, 1]
  kViewVideo,      // text = raw | undistorted
  kViewMode,       // text = auto | ar | vr
  kViewReported,   // value != 0: show the reported ghost
  kViewPredicted,  // value != 0: show the predicted arm
  kViewCapture,    // value != 0: show the arm at the frame's capture
  kViewPlots,      // value != 0: show the Plots panel
  // registration capture (the Registration panel)
  kCaptureOpen,   // text = folder, spec = the target (empty: the robot's marker)
  kCaptureAdd,    // the pose the real arm is at
  kCaptureSolve,  // register with the poses so far
  kCaptureClose,
  // automation
  kScreenshot,  // text = path
  kQuit,
};

struct UiAction {
  ActionKind kind = ActionKind::kQuit;
  int index = 0;
  int index2 = 0;
  double value = 0.0;
  core::MotionFrame frame = core::MotionFrame::kBase;
  Eigen::Vector3d dX = Eigen::Vector3d::Zero();
  Eigen::Vector3d dM = Eigen::Vector3d::Zero();
  Eigen::VectorXd q{};
  std::string text{};
  std::string spec{};  // a second text argument: registration open's target
};

// "ghost joint", "plan add" ...: for messages.
const char* to_string(ActionKind kind);

}  // namespace telear::console
