#pragma once
// Mouse jogging over the stereo view: with the right button held over the view, dragging
// moves the tool in the selected frame (horizontal drag: +-y, vertical drag: +-z, 20 pixels
// per Cartesian step) and the wheel moves it along x (one step per notch). The view panel
// says each frame whether the mouse is over the view.

#include "telear/console/input_device.hpp"

namespace telear::console {

class MouseInput final : public InputDevice {
 public:
  std::string name() const override { return "mouse"; }
  bool available() const override { return true; }
  void set_over_view(bool over) { over_view_ = over; }
  std::vector<InputIncrement> poll(double dt, const InputSteps& steps) override;

  static constexpr double kPixelsPerStep = 20.0;

 private:
  bool over_view_ = false;
};

}  // namespace telear::console
