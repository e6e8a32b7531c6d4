#pragma once
// Plays a parsed UI script (ui_script.hpp) against the console, one display frame at a time:
// each frame it applies actions until it reaches a wait (which lasts display time, during
// which the session keeps running) or a screenshot (taken at the end of this frame). A failed
// action or a wait-until that times out is reported with its line and counted; the script
// goes on, so that one run shows every problem. `registration add` runs on the capture's
// worker (the console stays live): the next line waits until it is done, and a failed add is
// reported on its line like any failed action.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "telear/console/ui_script.hpp"
#include "telear/console/ui_state.hpp"
#include "telear/session/session.hpp"

namespace telear::console {

class ScriptRunner {
 public:
  ScriptRunner() = default;
  explicit ScriptRunner(std::vector<ScriptLine> lines) : lines_(std::move(lines)) {}

  // One display frame at session time `now` (s). `report` receives failures.
  void step(session::Session& session, UiState& ui, double now,
            const std::function<void(const std::string&)>& report);

  bool finished() const { return next_ >= lines_.size() && !waiting_ && !add_line_; }
  bool empty() const { return lines_.empty(); }
  int failures() const { return failures_; }
  std::size_t position() const { return next_; }

 private:
  bool condition_met(session::Session& session, Condition condition) const;
  // True while the last `registration add` is still running (its failure reported when done).
  bool add_running(session::Session& session,
                   const std::function<void(const std::string&)>& report);

  std::vector<ScriptLine> lines_;
  std::size_t next_ = 0;
  bool waiting_ = false;
  double wait_until_ = 0.0;     // WaitFor: session time it ends
  double wait_deadline_ = 0.0;  // WaitUntil: timeout
  int failures_ = 0;
  // A `registration add` in flight: its line and the capture's finished adds before it.
  std::optional<std::size_t> add_line_;  // index into lines_
  int adds_before_ = 0;
};

}  // namespace telear::console
