#pragma once
// The servers the console starts in its own process when it is given no addresses (the
// embedded default). The console knows them through this interface only: the program that
// starts the console chooses what runs behind it -- `telear console` starts lab's simulated
// robot and stereo rig (src/apps/console_command.cpp) -- so the console links no simulator.

#include <functional>
#include <memory>
#include <string>

#include "telear/core/result.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/core/robot_model.hpp"
#include "telear/vision/camera_model.hpp"

namespace telear::console {

class LocalServers {
 public:
  virtual ~LocalServers() = default;
  virtual std::string robot_address() const = 0;
  virtual std::string vision_address() const = 0;
  virtual const std::string& token() const = 0;  // both servers'
  // The cameras the AR view draws with when no calibration file is given (a simulator's are
  // its true cameras).
  virtual const vision::StereoCameraModel& cameras() const = 0;
  // Shuts both down (a lost connection, in tests); the destructor stops them too.
  virtual void stop() = 0;
};

// Starts the servers for this arm; `calibration_file` (may be empty) is the stereo calibration
// the vision server serves; `token` the servers' bearer token (empty: a random one). Errors name
// what could not be started.
using LocalServersStarter = std::function<Result<std::unique_ptr<LocalServers>>(
    core::RobotModelPtr model, const core::RobotDescription& description,
    const std::string& calibration_file, const std::string& token)>;

}  // namespace telear::console
