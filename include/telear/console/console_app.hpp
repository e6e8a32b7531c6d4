#pragma once
// The operator console: the main loop that draws a Session (telear/session/session.hpp) with Dear
// ImGui and the stereo AR view (telear/render/ar_view.hpp).
//
// It owns, in this order: the local servers (when started without addresses), the
// Session, the GL context (a GLFW window, or an EGL context and an off-screen frame buffer of
// the window's size with --headless), the ArView, ImGui, the input devices, the script runner
// and the optional full-screen eye windows. It keeps no state of its own beyond the UiState:
// the ghost, the plan, the real robot and the connection are the Session's.
//
// One frame: poll input (window events, E-STOP shortcut, input devices) -> script step ->
// session.update(dt) -> ArView render -> panels -> ImGui render into the window or the frame
// buffer -> screenshot if asked -> swap, eye windows.

#include <chrono>
#include <memory>
#include <ostream>
#include <string>

#include "telear/console/console_options.hpp"
#include "telear/console/local_servers.hpp"
#include "telear/console/script_runner.hpp"
#include "telear/console/ui_state.hpp"
#include "telear/core/image.hpp"
#include "telear/core/result.hpp"
#include "telear/record/session_recorder.hpp"
#include "telear/session/session.hpp"

namespace telear::console {

class ConsoleApp {
 public:
  // Errors: the robot model, the calibration, the servers, the script (its parse error names
  // the line), no GL context or window.
  static Result<std::unique_ptr<ConsoleApp>> create(const ConsoleOptions& options,
                                                    std::ostream& log);
  ~ConsoleApp();
  ConsoleApp(const ConsoleApp&) = delete;
  ConsoleApp& operator=(const ConsoleApp&) = delete;

  // One display frame; false when the console should close (window closed, `quit`, or the
  // frames and the script are done).
  bool frame();
  // frame() until it returns false; writes --screenshot; returns the exit status (0, or 1
  // when a script line failed or the screenshot could not be written).
  int run();

  session::Session& session() { return *session_; }
  UiState& ui() { return ui_; }
  LocalServers* servers() { return servers_.get(); }  // null when given addresses
  const ScriptRunner& script() const { return script_; }
  int frames_drawn() const { return frames_; }
  // The console's last drawn image (the whole window), RGB, top row first.
  const core::Image& last_image() const { return last_image_; }
  // Ends the --record recording (the file is then complete) and returns what it wrote; an
  // error when there is none or it failed. run() and the destructor end it too.
  Result<record::RecordingCounts> stop_recording();
  // The AR view as the last frame drew it (both eyes composed, without the panels), RGB, top
  // row first: what `telear replay` draws from the recording (tests compare the two).
  core::Image read_view_image() const;
  // Captures the image at the end of every frame (tests), not only on a screenshot.
  void set_capture_every_frame(bool on) { capture_every_frame_ = on; }

 private:
  struct Impl;
  explicit ConsoleApp(std::unique_ptr<Impl> impl);
  void rebuild_session();

  std::unique_ptr<Impl> impl_;
  std::unique_ptr<LocalServers> servers_;
  std::unique_ptr<session::Session> session_;
  UiState ui_;
  ScriptRunner script_;
  core::Image last_image_;
  bool capture_every_frame_ = false;
  int frames_ = 0;
};

}  // namespace telear::console
