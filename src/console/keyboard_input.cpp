#include "telear/console/keyboard_input.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

namespace telear::console {

std::vector<InputIncrement> KeyboardInput::poll(double /*dt*/, const InputSteps& steps) {
  std::vector<InputIncrement> out;
  const ImGuiIO& io = ImGui::GetIO();
  if (io.WantTextInput) return out;
  static const int plus[] = {GLFW_KEY_Q, GLFW_KEY_W, GLFW_KEY_E,
                             GLFW_KEY_R, GLFW_KEY_T, GLFW_KEY_Y};
  static const int minus[] = {GLFW_KEY_A, GLFW_KEY_S, GLFW_KEY_D,
                              GLFW_KEY_F, GLFW_KEY_G, GLFW_KEY_H};
  for (int j = 0; j < 6 && j < steps.dof; ++j) {
    for (int sign : {+1, -1}) {
      if (ImGui::IsKeyPressed(sign > 0 ? plus[j] : minus[j], true)) {
        InputIncrement inc;
        inc.kind = InputIncrement::Kind::kJoint;
        inc.joint = j;
        inc.delta = sign * steps.joint_rad;
        out.push_back(inc);
      }
    }
  }
  const bool rotate = io.KeyShift;
  const struct {
    int key, axis, sign;
  } cartesian[] = {{GLFW_KEY_RIGHT, 0, +1}, {GLFW_KEY_LEFT, 0, -1},    {GLFW_KEY_UP, 1, +1},
                   {GLFW_KEY_DOWN, 1, -1},  {GLFW_KEY_PAGE_UP, 2, +1}, {GLFW_KEY_PAGE_DOWN, 2, -1}};
  for (const auto& c : cartesian) {
    if (!ImGui::IsKeyPressed(c.key, true)) continue;
    InputIncrement inc;
    inc.kind = InputIncrement::Kind::kCartesian;
    inc.frame = steps.frame;
    if (rotate) {
      inc.dM[c.axis] = c.sign * steps.rotation_rad;
    } else {
      inc.dX[c.axis] = c.sign * steps.cartesian_m;
    }
    out.push_back(inc);
  }
  for (auto [key, opening] : {std::pair{GLFW_KEY_O, 1.0}, std::pair{GLFW_KEY_C, 0.0}}) {
    if (ImGui::IsKeyPressed(key, false)) {
      InputIncrement inc;
      inc.kind = InputIncrement::Kind::kGripper;
      inc.delta = opening;
      out.push_back(inc);
    }
  }
  return out;
}

}  // namespace telear::console
