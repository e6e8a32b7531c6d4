#include "telear/console/eye_windows.hpp"

#include <epoxy/gl.h>
// epoxy first: GLFW must not include the system GL header.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace telear::console {

namespace {

GLFWwindow* open_window(GLFWmonitor* monitor, int width, int height, const char* title,
                        GLFWwindow* share) {
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_STEREO, GLFW_FALSE);
  glfwWindowHint(GLFW_VISIBLE, GLFW_TRUE);
  if (monitor) {
    const GLFWvidmode* mode = glfwGetVideoMode(monitor);
    width = mode->width;
    height = mode->height;
  }
  return glfwCreateWindow(width, height, title, monitor, share);
}

}  // namespace

Result<std::unique_ptr<EyeWindows>> EyeWindows::create(render::GlfwContext& main,
                                                       bool two_windows) {
  std::unique_ptr<EyeWindows> eyes(new EyeWindows());
  eyes->main_ = &main;
  eyes->two_windows_ = two_windows;
  int count = 0;
  GLFWmonitor** monitors = glfwGetMonitors(&count);
  if (two_windows) {
    const bool two_monitors = count >= 2;
    for (int i = 0; i < 2; ++i) {
      eyes->windows_[i] =
          open_window(two_monitors ? monitors[i] : nullptr, 960, 540,
                      i == 0 ? "telear left eye" : "telear right eye", main.window());
      if (!eyes->windows_[i]) return Error{"fullscreen_eyes: cannot open the eye windows"};
      if (!two_monitors) glfwSetWindowPos(eyes->windows_[i], i * 970, 40);
    }
  } else {
    eyes->windows_[0] = open_window(count > 0 ? monitors[count - 1] : nullptr, 1920, 540,
                                    "telear stereo (side by side)", main.window());
    if (!eyes->windows_[0]) return Error{"fullscreen_eyes: cannot open the stereo window"};
  }
  for (GLFWwindow* w : eyes->windows_) {
    if (!w) continue;
    glfwMakeContextCurrent(w);
    glfwSwapInterval(0);
  }
  (void)main.make_current();
  return eyes;
}

EyeWindows::~EyeWindows() {
  for (int i = 0; i < 2; ++i) {
    if (!windows_[i]) continue;
    glfwMakeContextCurrent(windows_[i]);
    if (read_framebuffers_[i]) glDeleteFramebuffers(1, &read_framebuffers_[i]);
    glfwDestroyWindow(windows_[i]);
  }
  if (main_) (void)main_->make_current();
}

void EyeWindows::present(unsigned left_texture, unsigned right_texture, int eye_width,
                         int eye_height) {
  const unsigned textures[2] = {left_texture, right_texture};
  for (int i = 0; i < 2; ++i) {
    GLFWwindow* w = windows_[i];
    if (!w) continue;
    glfwMakeContextCurrent(w);
    if (read_framebuffers_[i] == 0) glGenFramebuffers(1, &read_framebuffers_[i]);
    int fb_w = 0, fb_h = 0;
    glfwGetFramebufferSize(w, &fb_w, &fb_h);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, read_framebuffers_[i]);
    const int eyes_here = two_windows_ ? 1 : 2;
    for (int e = 0; e < eyes_here; ++e) {
      const unsigned texture = two_windows_ ? textures[i] : textures[e];
      glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture, 0);
      const int x0 = e * fb_w / eyes_here, x1 = (e + 1) * fb_w / eyes_here;
      glBlitFramebuffer(0, 0, eye_width, eye_height, x0, 0, x1, fb_h, GL_COLOR_BUFFER_BIT,
                        GL_LINEAR);
    }
    glfwSwapBuffers(w);
  }
  (void)main_->make_current();
}

}  // namespace telear::console
