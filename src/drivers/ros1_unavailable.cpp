// The ROS 1 driver's entry points in a build without ROS 1 (TELEAR_WITH_ROS1=OFF).
#include "telear/drivers/ros1_robot_driver.hpp"

namespace telear::drivers {

bool ros1_driver_built() {
  return false;
}

Result<std::unique_ptr<core::RobotDriver>> make_ros1_robot_driver(const core::RobotDescription&,
                                                                  const Ros1DriverOptions&) {
  return Error{
      "this telear was built without the ROS 1 driver (TELEAR_WITH_ROS1=OFF: configure "
      "with Debian's ROS 1 packages installed, scripts/install-deps.sh)"};
}

}  // namespace telear::drivers
