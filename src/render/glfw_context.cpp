#include "telear/render/glfw_context.hpp"

#include <epoxy/gl.h>
// epoxy first: GLFW must not pull in a GL header of its own.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <mutex>

namespace telear::render {
namespace {

// GLFW is process-global: initialise it with the first window, terminate it with the last.
std::mutex g_glfw_mutex;
int g_glfw_windows = 0;

Status acquire_glfw() {
  std::lock_guard<std::mutex> lock(g_glfw_mutex);
  if (g_glfw_windows == 0 && glfwInit() != GLFW_TRUE) {
    const char* description = nullptr;
    glfwGetError(&description);
    return Error{std::string("cannot initialise GLFW (no display?): ") +
                 (description ? description : "unknown reason")};
  }
  ++g_glfw_windows;
  return Status::Ok();
}

void release_glfw() {
  std::lock_guard<std::mutex> lock(g_glfw_mutex);
  if (--g_glfw_windows == 0) glfwTerminate();
}

GLFWwindow* create_window(const GlfwOptions& o, bool stereo) {
  glfwDefaultWindowHints();
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_VISIBLE, o.visible ? GLFW_TRUE : GLFW_FALSE);
  glfwWindowHint(GLFW_DEPTH_BITS, 24);
  glfwWindowHint(GLFW_SAMPLES, o.samples);
  glfwWindowHint(GLFW_STEREO, stereo ? GLFW_TRUE : GLFW_FALSE);
  return glfwCreateWindow(o.width, o.height, o.title.c_str(), nullptr, nullptr);
}

}  // namespace

Result<std::unique_ptr<GlfwContext>> GlfwContext::create(const GlfwOptions& options) {
  if (Status s = acquire_glfw(); !s) return s.error();
  GLFWwindow* window = nullptr;
  if (options.request_stereo) {
    // Drivers without quad-buffered visuals refuse the window (GLFW_FORMAT_UNAVAILABLE);
    // fall back to a mono window rather than fail.
    window = create_window(options, true);
  }
  if (window == nullptr) window = create_window(options, false);
  if (window == nullptr) {
    const char* description = nullptr;
    glfwGetError(&description);
    release_glfw();
    return Error{std::string("cannot create a GLFW window with an OpenGL 3.3 core context: ") +
                 (description ? description : "unknown reason")};
  }
  std::unique_ptr<GlfwContext> context(new GlfwContext());
  context->window_ = window;
  glfwMakeContextCurrent(window);
  glfwSwapInterval(options.vsync ? 1 : 0);
  context->stereo_requested_ = options.request_stereo;
  GLboolean stereo = GL_FALSE;
  glGetBooleanv(GL_STEREO, &stereo);
  context->stereo_granted_ = stereo == GL_TRUE;
  return context;
}

GlfwContext::~GlfwContext() {
  if (window_ == nullptr) return;
  if (glfwGetCurrentContext() == window_) glfwMakeContextCurrent(nullptr);
  glfwDestroyWindow(window_);
  release_glfw();
}

Status GlfwContext::make_current() {
  glfwMakeContextCurrent(window_);
  if (glfwGetCurrentContext() != window_) return Error{"cannot make the GLFW window current"};
  return Status::Ok();
}

void GlfwContext::swap_buffers() {
  glfwSwapBuffers(window_);
}

std::string GlfwContext::description() const {
  return std::string("GLFW window") + (stereo_granted_ ? " (quad-buffer stereo)" : "");
}

bool GlfwContext::should_close() const {
  return glfwWindowShouldClose(window_) == GLFW_TRUE;
}

void GlfwContext::framebuffer_size(int& width, int& height) const {
  glfwGetFramebufferSize(window_, &width, &height);
}

}  // namespace telear::render
