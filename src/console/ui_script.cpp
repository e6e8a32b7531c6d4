#include "telear/console/ui_script.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "telear/core/angles.hpp"
#include "telear/core/number_list.hpp"

namespace telear::console {

namespace {

struct ParseError {
  std::string message;
};

std::vector<std::string> split_words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

double parse_double(const std::string& text, const std::string& what) {
  auto value = core::parse_number(text, what);
  if (!value) throw ParseError{value.error().message};
  return *value;
}

// An angle (degrees unless "rad" or "deg" suffix) in radians.
double parse_angle(const std::string& text) {
  if (text.size() > 3 && text.ends_with("rad")) {
    return parse_double(text.substr(0, text.size() - 3), "angle");
  }
  std::string number = text;
  if (number.size() > 3 && number.ends_with("deg")) number = number.substr(0, number.size() - 3);
  return core::radians_from_degrees(parse_double(number, "angle"));
}

// A length (metres unless "mm" or "m" suffix) in metres.
double parse_length(const std::string& text) {
  if (text.size() > 2 && text.ends_with("mm")) {
    return parse_double(text.substr(0, text.size() - 2), "length") / 1000.0;
  }
  std::string number = text;
  if (number.size() > 1 && number.ends_with("m")) number = number.substr(0, number.size() - 1);
  return parse_double(number, "length");
}

int parse_int(const std::string& text, const std::string& what) {
  const double v = parse_double(text, what);
  if (v != std::floor(v) || std::abs(v) > 1e6)
    throw ParseError{what + ": '" + text + "' is not a whole number"};
  return static_cast<int>(v);
}

void need(const std::vector<std::string>& w, std::size_t at_least, std::size_t at_most,
          const std::string& usage) {
  if (w.size() < at_least || w.size() > at_most) throw ParseError{"usage: " + usage};
}

int parse_joint(const std::string& text, int dof) {
  const int j = parse_int(text, "joint");
  if (j < 1 || j > dof) {
    throw ParseError{"joint " + text + " out of range 1.." + std::to_string(dof)};
  }
  return j - 1;
}

core::MotionFrame parse_frame(const std::string& text) {
  if (text == "base") return core::MotionFrame::kBase;
  if (text == "wrist") return core::MotionFrame::kWrist;
  if (text == "tool") return core::MotionFrame::kTool;
  throw ParseError{"frame '" + text + "': base, wrist or tool"};
}

// `cartesian FRAME AXIS DELTA` starting at w[i].
void parse_cartesian(const std::vector<std::string>& w, std::size_t i, UiAction& a) {
  a.frame = parse_frame(w[i]);
  const std::string& axis = w[i + 1];
  static const char* names[] = {"x", "y", "z", "rx", "ry", "rz"};
  int k = -1;
  for (int n = 0; n < 6; ++n) {
    if (axis == names[n]) k = n;
  }
  if (k < 0) throw ParseError{"axis '" + axis + "': x, y, z, rx, ry or rz"};
  if (k < 3) {
    a.dX[k] = parse_length(w[i + 2]);
  } else {
    a.dM[k - 3] = parse_angle(w[i + 2]);
  }
}

double parse_gripper(const std::string& text) {
  if (text == "open") return 1.0;
  if (text == "close" || text == "closed") return 0.0;
  const double v = parse_double(text, "gripper");
  if (v < 0.0 || v > 1.0) throw ParseError{"gripper " + text + ": open, close or 0..1"};
  return v;
}

std::string rest(const std::vector<std::string>& w, std::size_t from) {
  std::string out;
  for (std::size_t i = from; i < w.size(); ++i) out += (out.empty() ? "" : " ") + w[i];
  return out;
}

ScriptLine parse_line(const std::vector<std::string>& w, int dof) {
  ScriptLine line;
  UiAction a;
  const std::string& verb = w[0];
  const std::string sub = w.size() > 1 ? w[1] : "";
  auto action = [&](ActionKind kind) {
    a.kind = kind;
    line.step = a;
    return line;
  };
  if (verb == "connect") return need(w, 1, 1, "connect"), action(ActionKind::kConnect);
  if (verb == "disconnect") return need(w, 1, 1, "disconnect"), action(ActionKind::kDisconnect);
  if (verb == "take-control")
    return need(w, 1, 1, "take-control"), action(ActionKind::kTakeControl);
  if (verb == "release-control") {
    return need(w, 1, 1, "release-control"), action(ActionKind::kReleaseControl);
  }
  if (verb == "estop") return need(w, 1, 1, "estop"), action(ActionKind::kEStop);
  if (verb == "reset-estop") return need(w, 1, 1, "reset-estop"), action(ActionKind::kResetEStop);
  if (verb == "validate") return need(w, 1, 1, "validate"), action(ActionKind::kValidate);
  if (verb == "execute") return need(w, 1, 1, "execute"), action(ActionKind::kExecute);
  if (verb == "cancel") return need(w, 1, 1, "cancel"), action(ActionKind::kCancel);
  if (verb == "quit") return need(w, 1, 1, "quit"), action(ActionKind::kQuit);
  if (verb == "screenshot") {
    need(w, 2, 2, "screenshot FILE.png");
    a.text = w[1];
    return action(ActionKind::kScreenshot);
  }
  if (verb == "wait") {
    need(w, 2, 2, "wait SECONDS");
    const double s = parse_double(w[1], "wait");
    if (s < 0 || s > 3600) throw ParseError{"wait " + w[1] + ": 0..3600 s"};
    line.step = WaitFor{s};
    return line;
  }
  if (verb == "wait-until") {
    need(w, 2, 3,
         "wait-until idle|connected|disconnected|video|preview-end|in-control|ar [TIMEOUT_S]");
    WaitUntil u;
    static const std::pair<const char*, Condition> conditions[] = {
        {"idle", Condition::kIdle},
        {"connected", Condition::kConnected},
        {"disconnected", Condition::kDisconnected},
        {"video", Condition::kVideo},
        {"preview-end", Condition::kPreviewEnd},
        {"in-control", Condition::kInControl},
        {"ar", Condition::kAr}};
    bool found = false;
    for (const auto& [name, c] : conditions) {
      if (sub == name) {
        u.condition = c;
        found = true;
      }
    }
    if (!found) {
      throw ParseError{"condition '" + sub +
                       "': idle, connected, disconnected, video, preview-end, in-control or ar"};
    }
    if (w.size() == 3) {
      u.timeout_s = parse_double(w[2], "timeout");
      if (u.timeout_s <= 0 || u.timeout_s > 3600)
        throw ParseError{"timeout " + w[2] + ": 0..3600 s"};
    }
    line.step = u;
    return line;
  }
  if (verb == "ghost" || verb == "real") {
    const bool ghost = verb == "ghost";
    std::size_t i = 1;
    if (!ghost && sub == "jog") i = 2;
    const std::string what = w.size() > i ? w[i] : "";
    if (what == "joint" && (ghost || i == 2)) {
      need(w, i + 3, i + 3, verb + (ghost ? "" : " jog") + " joint N DELTA");
      a.index = parse_joint(w[i + 1], dof);
      a.value = parse_angle(w[i + 2]);
      return action(ghost ? ActionKind::kGhostJoint : ActionKind::kRealJoint);
    }
    if (what == "cartesian" && (ghost || i == 2)) {
      need(w, i + 4, i + 4, verb + (ghost ? "" : " jog") + " cartesian base|wrist|tool AXIS DELTA");
      parse_cartesian(w, i + 1, a);
      return action(ghost ? ActionKind::kGhostCartesian : ActionKind::kRealCartesian);
    }
    if (what == "gripper" && i == 1) {
      need(w, 3, 3, verb + " gripper open|close|0..1");
      a.value = parse_gripper(w[2]);
      return action(ghost ? ActionKind::kGhostGripper : ActionKind::kRealGripper);
    }
    if (ghost && what == "named") {
      need(w, 3, 3, "ghost named NAME");
      a.text = w[2];
      return action(ActionKind::kGhostNamed);
    }
    if (ghost && what == "reset")
      return need(w, 2, 2, "ghost reset"), action(ActionKind::kGhostToReal);
    if (!ghost && what == "initialize") {
      need(w, 3, 3, "real initialize NAME | Q1,Q2,... (degrees)");
      const std::string& arg = w[2];
      if (arg.find(',') == std::string::npos && !arg.empty() &&
          (std::isalpha(static_cast<unsigned char>(arg[0])) != 0)) {
        a.text = arg;
      } else {
        std::vector<double> values;
        std::stringstream in(arg);
        for (std::string item; std::getline(in, item, ',');) values.push_back(parse_angle(item));
        if (static_cast<int>(values.size()) != dof) {
          throw ParseError{"real initialize: " + std::to_string(dof) +
                           " joint values needed, got " + std::to_string(values.size())};
        }
        a.q = Eigen::Map<Eigen::VectorXd>(values.data(), dof);
      }
      return action(ActionKind::kRealInitialize);
    }
    throw ParseError{"unknown " + verb + " action '" + rest(w, 1) + "' (" +
                     (ghost ? "joint, cartesian, gripper, named, reset"
                            : "jog joint, jog cartesian, gripper, initialize") +
                     ")"};
  }
  if (verb == "plan") {
    if (sub == "add") {
      need(w, 2, 99, "plan add [DURATION_S [LABEL...]]");
      if (w.size() > 2) a.value = parse_double(w[2], "duration");
      if (a.value < 0) throw ParseError{"duration " + w[2] + " must be >= 0"};
      a.text = rest(w, 3);
      return action(ActionKind::kPlanAdd);
    }
    if (sub == "delete") {
      need(w, 3, 3, "plan delete N");
      a.index = parse_int(w[2], "waypoint") - 1;
      return action(ActionKind::kPlanDelete);
    }
    if (sub == "move") {
      need(w, 4, 4, "plan move FROM TO");
      a.index = parse_int(w[2], "waypoint") - 1;
      a.index2 = parse_int(w[3], "waypoint") - 1;
      return action(ActionKind::kPlanMove);
    }
    if (sub == "duration") {
      need(w, 4, 4, "plan duration N SECONDS");
      a.index = parse_int(w[2], "waypoint") - 1;
      a.value = parse_double(w[3], "duration");
      return action(ActionKind::kPlanDuration);
    }
    if (sub == "clear") return need(w, 2, 2, "plan clear"), action(ActionKind::kPlanClear);
    if (sub == "save" || sub == "load") {
      need(w, 3, 3, "plan " + sub + " FILE");
      a.text = w[2];
      return action(sub == "save" ? ActionKind::kPlanSave : ActionKind::kPlanLoad);
    }
    throw ParseError{"unknown plan action '" + sub +
                     "' (add, delete, move, duration, clear, save, load)"};
  }
  if (verb == "preview") {
    if (sub == "play") return need(w, 2, 2, "preview play"), action(ActionKind::kPreviewPlay);
    if (sub == "pause") return need(w, 2, 2, "preview pause"), action(ActionKind::kPreviewPause);
    if (sub == "stop") return need(w, 2, 2, "preview stop"), action(ActionKind::kPreviewStop);
    if (sub == "seek" || sub == "speed") {
      need(w, 3, 3, "preview " + sub + " VALUE");
      a.value = parse_double(w[2], sub);
      return action(sub == "seek" ? ActionKind::kPreviewSeek : ActionKind::kPreviewSpeed);
    }
    throw ParseError{"unknown preview action '" + sub + "' (play, pause, stop, seek, speed)"};
  }
  if (verb == "registration") {
    if (sub == "open") {
      need(w, 3, 4, "registration open FOLDER [TARGET]");
      a.text = w[2];
      if (w.size() == 4) a.spec = w[3];
      return action(ActionKind::kCaptureOpen);
    }
    if (sub == "add") return need(w, 2, 2, "registration add"), action(ActionKind::kCaptureAdd);
    if (sub == "solve")
      return need(w, 2, 2, "registration solve"), action(ActionKind::kCaptureSolve);
    if (sub == "close")
      return need(w, 2, 2, "registration close"), action(ActionKind::kCaptureClose);
    throw ParseError{"unknown registration action '" + sub + "' (open, add, solve, close)"};
  }
  if (verb == "view") {
    need(w, 3, 3,
         "view layout|style|segments|opacity|video|mode|reported|predicted|capture|plots VALUE");
    a.text = w[2];
    if (sub == "layout") return action(ActionKind::kViewLayout);
    if (sub == "style") return action(ActionKind::kViewStyle);
    if (sub == "video") return action(ActionKind::kViewVideo);
    if (sub == "mode") return action(ActionKind::kViewMode);
    if (sub == "segments") {
      a.index = parse_int(w[2], "segments");
      return action(ActionKind::kViewSegments);
    }
    if (sub == "opacity") {
      a.value = parse_double(w[2], "opacity");
      return action(ActionKind::kViewOpacity);
    }
    if (sub == "reported" || sub == "predicted" || sub == "capture" || sub == "plots") {
      if (w[2] != "on" && w[2] != "off") throw ParseError{"view " + sub + " on|off"};
      a.value = w[2] == "on" ? 1.0 : 0.0;
      return action(sub == "reported"    ? ActionKind::kViewReported
                    : sub == "predicted" ? ActionKind::kViewPredicted
                    : sub == "capture"   ? ActionKind::kViewCapture
                                         : ActionKind::kViewPlots);
    }
    throw ParseError{
        "unknown view setting '" + sub +
        "' (layout, style, segments, opacity, video, mode, reported, predicted, capture, plots)"};
  }
  throw ParseError{
      "unknown command '" + verb +
      "' (connect, disconnect, take-control, release-control, estop, reset-estop, "
      "ghost, real, plan, preview, validate, execute, cancel, registration, view, wait, "
      "wait-until, screenshot, quit)"};
}

}  // namespace

Result<std::vector<ScriptLine>> parse_ui_script(const std::string& text, int dof,
                                                const std::string& source) {
  std::vector<ScriptLine> lines;
  std::istringstream in(text);
  int number = 0;
  for (std::string raw; std::getline(in, raw);) {
    ++number;
    std::string line = raw.substr(0, raw.find('#'));
    const auto words = split_words(line);
    if (words.empty()) continue;
    try {
      ScriptLine parsed = parse_line(words, dof);
      parsed.line = number;
      parsed.text = rest(words, 0);
      lines.push_back(std::move(parsed));
    } catch (const ParseError& e) {
      return Error{source + ", line " + std::to_string(number) + ": " + rest(words, 0) + ": " +
                   e.message};
    }
  }
  return lines;
}

Result<std::vector<ScriptLine>> load_ui_script(const std::string& path, int dof) {
  std::ifstream in(path);
  if (!in) return Error{"script '" + path + "': cannot be read"};
  std::stringstream text;
  text << in.rdbuf();
  return parse_ui_script(text.str(), dof, "script '" + path + "'");
}

const char* to_string(Condition condition) {
  switch (condition) {
    case Condition::kIdle:
      return "idle";
    case Condition::kConnected:
      return "connected";
    case Condition::kDisconnected:
      return "disconnected";
    case Condition::kVideo:
      return "video";
    case Condition::kPreviewEnd:
      return "preview-end";
    case Condition::kInControl:
      return "in-control";
    case Condition::kAr:
      return "ar";
  }
  return "?";
}

}  // namespace telear::console
