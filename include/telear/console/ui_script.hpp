#pragma once
// `--script FILE`: UI actions replayed line by line (tests, documentation, demos).
//
// One action per line; blank lines and text after '#' are ignored; words are separated by
// blanks. Joints and waypoints count from 1. Angles are in degrees unless suffixed `rad`,
// lengths in metres unless suffixed `mm` (e.g. `+5deg`, `-0.02`, `20mm`, `0.1rad`).
//
//   connect | disconnect | take-control | release-control | estop | reset-estop
//   ghost joint N DELTA            ghost cartesian base|wrist|tool x|y|z|rx|ry|rz DELTA
//   ghost gripper open|close|F     ghost named NAME             ghost reset   (ghost = real)
//   real jog joint N DELTA         real jog cartesian FRAME AXIS DELTA
//   real gripper open|close|F      real initialize NAME | Q1,Q2,...  (degrees)
//   plan add [DURATION_S [LABEL...]]   plan delete N   plan move FROM TO
//   plan duration N SECONDS        plan clear   plan save FILE   plan load FILE
//   preview play|pause|stop        preview seek SECONDS   preview speed S
//   validate | execute | cancel
//   view layout sbs|tb|anaglyph|left|right|separate|page-flip
//   view style solid|wire   view segments N   view opacity F   view video raw|undistorted
//   view mode auto|ar|vr    view reported on|off   view predicted on|off
//   view capture on|off     (the arm at the frame's capture time, over the video)
//   registration open FOLDER | add | solve | close   (the Registration panel's buttons)
//   wait SECONDS                                  (display time passes, the session runs)
//   wait-until idle|connected|disconnected|video|preview-end|in-control|ar [TIMEOUT_S]
//                                  (ar: the view shows the live video in AR)
//   screenshot FILE.png     quit
//
// Parsing is all-or-nothing: an error names the file and line ("script 's.txt', line 4:
// ghost joint 7: joint 7 out of range 1..6").

#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "telear/console/ui_action.hpp"
#include "telear/core/result.hpp"

namespace telear::console {

struct WaitFor {
  double seconds = 0.0;
};

enum class Condition { kIdle, kConnected, kDisconnected, kVideo, kPreviewEnd, kInControl, kAr };

struct WaitUntil {
  Condition condition = Condition::kIdle;
  double timeout_s = 60.0;
};

struct ScriptLine {
  int line = 0;      // 1-based line in the file
  std::string text;  // the line as written (for messages)
  std::variant<UiAction, WaitFor, WaitUntil> step;
};

// `dof` bounds the joint numbers; `source` names the text in messages.
Result<std::vector<ScriptLine>> parse_ui_script(const std::string& text, int dof,
                                                const std::string& source = "script");
Result<std::vector<ScriptLine>> load_ui_script(const std::string& path, int dof);

const char* to_string(Condition condition);

}  // namespace telear::console
