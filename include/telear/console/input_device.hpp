#pragma once
// Where motion increments come from: the keyboard, the mouse, a gamepad or joystick -- or a
// master arm. Each device is polled once per display frame and yields the increments its
// operator asked for since the last poll, as joint increments (rad or m) or Cartesian
// increments (m, rad) in a frame; the console turns each into the same UiAction a button
// would make, for the ghost or, in the conventional mode, the real robot.
//
// Rate devices (a stick held over) scale by dt; step devices (a key press) give one step per
// press or key repeat. The step sizes are the operator's (UiState).

#include <string>
#include <vector>

#include "telear/core/motion_command.hpp"

namespace telear::console {

struct InputIncrement {
  enum class Kind { kJoint, kCartesian, kGripper } kind = Kind::kJoint;
  int joint = 0;       // kJoint: 0-based
  double delta = 0.0;  // kJoint: rad or m; kGripper: the opening asked for (0..1)
  core::MotionFrame frame = core::MotionFrame::kBase;
  Eigen::Vector3d dX = Eigen::Vector3d::Zero();  // kCartesian: m
  Eigen::Vector3d dM = Eigen::Vector3d::Zero();  // kCartesian: rad
};

struct InputSteps {
  double joint_rad = 0.035;
  double cartesian_m = 0.01;
  double rotation_rad = 0.087;
  core::MotionFrame frame = core::MotionFrame::kBase;
  int dof = 6;
};

class InputDevice {
 public:
  virtual ~InputDevice() = default;
  virtual std::string name() const = 0;
  // Whether the device is present now (a gamepad may be unplugged).
  virtual bool available() const = 0;
  // Increments since the last poll; dt in seconds since it.
  virtual std::vector<InputIncrement> poll(double dt, const InputSteps& steps) = 0;
};

}  // namespace telear::console
