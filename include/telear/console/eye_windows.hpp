#pragma once
// Full-screen output of each eye for a head-mounted or 3-D display (issue 7, item 4):
//
//   two-windows  one full-screen window per eye: the left eye on the first monitor, the right
//                on the second (with one monitor: two 960 x 540 windows side by side);
//   sbs          one full-screen window, on the last monitor (usually the HMD), showing the
//                left eye in its left half and the right eye in its right half (the side-by-
//                side format 3-D displays and HMDs take).
//
// The windows share the console's GL objects (textures are shared between GLFW contexts
// created with a share window; framebuffers are not, so each window has its own read
// framebuffer): present() blits the eye textures into them and swaps, without vsync so the
// console's loop is not held up three times.

#include <memory>

#include "telear/core/result.hpp"
#include "telear/render/glfw_context.hpp"

struct GLFWwindow;

namespace telear::console {

class EyeWindows {
 public:
  static Result<std::unique_ptr<EyeWindows>> create(render::GlfwContext& main, bool two_windows);
  ~EyeWindows();
  EyeWindows(const EyeWindows&) = delete;
  EyeWindows& operator=(const EyeWindows&) = delete;

  // Draws the eye textures (eye_width x eye_height, bottom-up) and leaves the main context
  // current.
  void present(unsigned left_texture, unsigned right_texture, int eye_width, int eye_height);

 private:
  EyeWindows() = default;
  render::GlfwContext* main_ = nullptr;
  GLFWwindow* windows_[2] = {nullptr, nullptr};
  unsigned read_framebuffers_[2] = {0, 0};
  bool two_windows_ = true;
};

}  // namespace telear::console
