#pragma once
// A gamepad or joystick through GLFW (the seed's joystick). Needs GLFW initialised (a window).
//
// A gamepad with a GLFW mapping (Xbox-like layout), rates at full deflection of 10 steps / s:
//   left stick   x: +-y, y: +-x          right stick  y: +-z, x: rotation about z
//   A: gripper close     B: gripper open (on press)
// A joystick without a mapping: axis k drives joint k (k < dof) at 10 joint steps / s.
// Deflections under 0.15 are ignored (dead zone).

#include "telear/console/input_device.hpp"

namespace telear::console {

class GamepadInput final : public InputDevice {
 public:
  std::string name() const override;
  bool available() const override;
  std::vector<InputIncrement> poll(double dt, const InputSteps& steps) override;

  static constexpr double kDeadZone = 0.15;
  static constexpr double kStepsPerSecond = 10.0;

 private:
  int joystick() const;  // the first present joystick id, or -1
  bool a_was_down_ = false, b_was_down_ = false;
};

}  // namespace telear::console
