#pragma once
// A window with an OpenGL 3.3 core context (GLFW), for the operator console and stereo
// viewing. Needs a display (X11 / Wayland, or Xvfb in tests).
//
// Stereo: with request_stereo the window asks for a quad-buffered visual (GLFW_STEREO);
// drivers that have none refuse such a window, and the context is then created again
// without it, so creation succeeds either way and stereo_granted() says what was obtained
// (checked with glGetBooleanv(GL_STEREO)). With stereo, draw into GL_BACK_LEFT and
// GL_BACK_RIGHT, then swap_buffers().

#include <memory>
#include <string>

#include "telear/core/result.hpp"
#include "telear/render/gl_context.hpp"

struct GLFWwindow;

namespace telear::render {

struct GlfwOptions {
  int width = 1280;
  int height = 720;
  std::string title = "telear";
  bool visible = true;
  bool request_stereo = false;
  bool vsync = true;
  int samples = 0;  // multisampling of the default framebuffer
};

class GlfwContext final : public GlContext {
 public:
  // Creates the window and makes its context current. Errors: GLFW cannot initialise (no
  // display), or no GL 3.3 core context.
  static Result<std::unique_ptr<GlfwContext>> create(const GlfwOptions& options = {});
  ~GlfwContext() override;

  Status make_current() override;
  void swap_buffers() override;
  std::string description() const override;

  bool stereo_requested() const { return stereo_requested_; }
  bool stereo_granted() const { return stereo_granted_; }
  bool should_close() const;
  // Framebuffer size in pixels (may differ from the window size on HiDPI screens).
  void framebuffer_size(int& width, int& height) const;
  GLFWwindow* window() const { return window_; }  // for input callbacks and ImGui

 private:
  GlfwContext() = default;
  GLFWwindow* window_ = nullptr;
  bool stereo_requested_ = false;
  bool stereo_granted_ = false;
};

}  // namespace telear::render
