#pragma once
// The window (or the headless frame buffer) and Dear ImGui that the console and the replay
// share: one set-up, one frame's begin and end, one read-back, so that `telear replay` looks
// and scripts like `telear console` (internal to the console library).
//
// Windowed: a GLFW window with ImGui's GLFW and OpenGL 3 back-ends. Headless: an EGL context
// and an off-screen target of the given size, ImGui fed its display size and time step by
// hand, its navigation keys mapped to GLFW's key codes (tests and scripts press the same keys
// as a window).

#include <memory>
#include <string>

#include "telear/core/image.hpp"
#include "telear/core/result.hpp"
#include "telear/render/gl_context.hpp"
#include "telear/render/glfw_context.hpp"
#include "telear/render/offscreen_target.hpp"

namespace telear::console {

struct GuiOptions {
  bool headless = false;
  int width = 1600, height = 1000;
  std::string title = "telear";
  bool request_stereo = false;  // a quad-buffered window (page-flipped stereo), when granted
};

class GuiContext {
 public:
  // Errors: no headless context, no window (with the xvfb-run hint), ImGui's GL back-end.
  static Result<std::unique_ptr<GuiContext>> create(const GuiOptions& options);
  ~GuiContext();
  GuiContext(const GuiContext&) = delete;
  GuiContext& operator=(const GuiContext&) = delete;

  render::GlfwContext* window() { return window_; }  // null when headless
  bool headless() const { return window_ == nullptr; }
  Status make_current() { return context_->make_current(); }

  // Polls the window's events and starts an ImGui frame; false when the window was closed.
  bool begin_frame(double dt);
  // Binds the window's back buffer (or the headless target), sets the viewport, clears:
  // ready for ImGui's draw data (or the caller's own drawing). Returns the size.
  void bind_output(int& width, int& height);
  // Reads the bound output back, RGB, top row first.
  core::Image read_output(int width, int height) const;
  void present();  // swaps a window's buffers; nothing headless

 private:
  GuiContext() = default;
  GuiOptions options_;
  std::unique_ptr<render::GlContext> context_;
  render::GlfwContext* window_ = nullptr;
  render::OffscreenTarget headless_target_;
  bool imgui_glfw_ = false, imgui_gl_ = false;
};

}  // namespace telear::console
