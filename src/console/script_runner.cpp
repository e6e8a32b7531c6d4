#include "telear/console/script_runner.hpp"

#include "telear/console/console_actions.hpp"

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
  }
  return false;
}

void ScriptRunner::step(session::Session& session, UiState& ui, double now,
                        const std::function<void(const std::string&)>& report) {
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
    if (Status s = apply_action(session, ui, action); !s.ok()) {
      ++failures_;
      report("line " + std::to_string(line.line) + ": " + line.text + ": " + s.error().message);
    }
    if (action.kind == ActionKind::kScreenshot || action.kind == ActionKind::kQuit) return;
  }
}

}  // namespace telear::console
