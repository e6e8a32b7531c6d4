#include "telear/console/script_runner.hpp"

#include "telear/console/console_actions.hpp"
#include "telear/session/capture_session.hpp"

namespace telear::console {

bool ScriptRunner::condition_met(session::Session& session, Condition condition) const {
  switch (condition) {
    case Condition::kIdle:
      return robot_idle(session);
    case Condition::kConnected:
      return session.robot_connected() && session.vision_connected() && session.view().real &&
             session.view().frame;
    case Condition::kDisconnected:
      return !session.robot_connected();
    case Condition::kVideo:
      return session.view().frame != nullptr;
    case Condition::kPreviewEnd: {
      auto* preview = session.preview();
      return preview == nullptr || preview->current().at_end;
    }
    case Condition::kInControl:
      return session.in_control();
    case Condition::kAr:
      return session.view().display.mode == session::DisplayMode::kAR;
  }
  return false;
}

bool ScriptRunner::add_running(session::Session& session,
                               const std::function<void(const std::string&)>& report) {
  if (!add_line_) return false;
  const session::CaptureSession* capture = session.capture();
  if (capture == nullptr) {  // closed meanwhile: the add was cancelled with it
    add_line_.reset();
    return false;
  }
  if (capture->adding() || capture->adds_finished() == adds_before_) return true;
  if (!capture->last_add_error().empty()) {
    ++failures_;
    const ScriptLine& line = lines_[*add_line_];
    report("line " + std::to_string(line.line) + ": " + line.text + ": " +
           capture->last_add_error());
  }
  add_line_.reset();
  return false;
}

void ScriptRunner::step(session::Session& session, UiState& ui, double now,
                        const std::function<void(const std::string&)>& report) {
  if (add_running(session, report)) return;
  if (waiting_) {
    const ScriptLine& line = lines_[next_ - 1];
    if (const auto* w = std::get_if<WaitUntil>(&line.step)) {
      if (condition_met(session, w->condition)) {
        waiting_ = false;
      } else if (now >= wait_deadline_) {
        waiting_ = false;
        ++failures_;
        report("line " + std::to_string(line.line) + ": " + line.text + ": not " +
               to_string(w->condition) + " after " + std::to_string(w->timeout_s) + " s");
      }
    } else if (now >= wait_until_) {
      waiting_ = false;
    }
    if (waiting_) return;
  }
  while (next_ < lines_.size()) {
    const ScriptLine& line = lines_[next_++];
    if (const auto* w = std::get_if<WaitFor>(&line.step)) {
      waiting_ = true;
      wait_until_ = now + w->seconds;
      return;
    }
    if (const auto* w = std::get_if<WaitUntil>(&line.step)) {
      if (condition_met(session, w->condition)) continue;
      waiting_ = true;
      wait_deadline_ = now + w->timeout_s;
      return;
    }
    const UiAction& action = std::get<UiAction>(line.step);
    const int adds_before = session.capture() ? session.capture()->adds_finished() : 0;
    if (Status s = apply_action(session, ui, action); !s.ok()) {
      ++failures_;
      report("line " + std::to_string(line.line) + ": " + line.text + ": " + s.error().message);
    } else if (action.kind == ActionKind::kCaptureAdd) {
      add_line_ = next_ - 1;
      adds_before_ = adds_before;
      return;
    }
    if (action.kind == ActionKind::kScreenshot || action.kind == ActionKind::kQuit) return;
  }
}

}  // namespace telear::console
