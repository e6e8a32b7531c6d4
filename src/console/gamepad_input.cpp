#include "telear/console/gamepad_input.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cmath>

namespace telear::console {

namespace {
double dead_zone(double v) {
  if (std::abs(v) < GamepadInput::kDeadZone) return 0.0;
  return (v - std::copysign(GamepadInput::kDeadZone, v)) / (1.0 - GamepadInput::kDeadZone);
}
}  // namespace

int GamepadInput::joystick() const {
  for (int jid = GLFW_JOYSTICK_1; jid <= GLFW_JOYSTICK_LAST; ++jid) {
    if (glfwJoystickPresent(jid) == GLFW_TRUE) return jid;
  }
  return -1;
}

bool GamepadInput::available() const {
  return joystick() >= 0;
}

std::string GamepadInput::name() const {
  const int jid = joystick();
  if (jid < 0) return "gamepad (none connected)";
  const char* n = glfwJoystickIsGamepad(jid) ? glfwGetGamepadName(jid) : glfwGetJoystickName(jid);
  return std::string(glfwJoystickIsGamepad(jid) ? "gamepad: " : "joystick: ") + (n ? n : "?");
}

std::vector<InputIncrement> GamepadInput::poll(double dt, const InputSteps& steps) {
  std::vector<InputIncrement> out;
  const int jid = joystick();
  if (jid < 0 || !(dt > 0.0) || dt > 0.5) return out;
  const double rate = kStepsPerSecond * dt;
  GLFWgamepadstate state;
  if (glfwJoystickIsGamepad(jid) && glfwGetGamepadState(jid, &state)) {
    InputIncrement inc;
    inc.kind = InputIncrement::Kind::kCartesian;
    inc.frame = steps.frame;
    inc.dX.y() = -dead_zone(state.axes[GLFW_GAMEPAD_AXIS_LEFT_X]) * rate * steps.cartesian_m;
    inc.dX.x() = -dead_zone(state.axes[GLFW_GAMEPAD_AXIS_LEFT_Y]) * rate * steps.cartesian_m;
    inc.dX.z() = -dead_zone(state.axes[GLFW_GAMEPAD_AXIS_RIGHT_Y]) * rate * steps.cartesian_m;
    inc.dM.z() = -dead_zone(state.axes[GLFW_GAMEPAD_AXIS_RIGHT_X]) * rate * steps.rotation_rad;
    if (!inc.dX.isZero() || !inc.dM.isZero()) out.push_back(inc);
    const bool a = state.buttons[GLFW_GAMEPAD_BUTTON_A] == GLFW_PRESS;
    const bool b = state.buttons[GLFW_GAMEPAD_BUTTON_B] == GLFW_PRESS;
    if (a && !a_was_down_) out.push_back({InputIncrement::Kind::kGripper, 0, 0.0});
    if (b && !b_was_down_) out.push_back({InputIncrement::Kind::kGripper, 0, 1.0});
    a_was_down_ = a;
    b_was_down_ = b;
    return out;
  }
  int count = 0;
  const float* axes = glfwGetJoystickAxes(jid, &count);
  for (int k = 0; axes && k < count && k < steps.dof; ++k) {
    const double v = dead_zone(axes[k]);
    if (v == 0.0) continue;
    InputIncrement inc;
    inc.kind = InputIncrement::Kind::kJoint;
    inc.joint = k;
    inc.delta = v * rate * steps.joint_rad;
    out.push_back(inc);
  }
  return out;
}

}  // namespace telear::console
