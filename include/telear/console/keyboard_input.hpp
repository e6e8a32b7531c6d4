#pragma once
// Keyboard jogging through Dear ImGui's key state (so it works in a GLFW window and, with
// keys fed by a test, headless), ignored while a text field has the keyboard:
//
//   Q / A  joint 1 + / -     W / S  joint 2     E / D  joint 3
//   R / F  joint 4           T / G  joint 5     Y / H  joint 6
//   arrows  +-x / +-y in the selected frame     Page Up / Page Down  +-z
//   Shift + arrows / pages: rotations about the same axes
//   O / C   gripper open / close
// One step per press, repeated while held (ImGui's key repeat).

#include "telear/console/input_device.hpp"

namespace telear::console {

class KeyboardInput final : public InputDevice {
 public:
  std::string name() const override { return "keyboard"; }
  bool available() const override { return true; }
  std::vector<InputIncrement> poll(double dt, const InputSteps& steps) override;
};

}  // namespace telear::console
