// The ROS 2 driver's entry points in a build without Cyclone DDS (TELEAR_WITH_ROS2=OFF).
#include "telear/drivers/ros2_robot_driver.hpp"

namespace telear::drivers {

bool ros2_driver_built() {
  return false;
}

Result<std::unique_ptr<core::RobotDriver>> make_ros2_robot_driver(const core::RobotDescription&,
                                                                  const Ros2DriverOptions&) {
  return Error{
      "this telear was built without the ROS 2 driver (TELEAR_WITH_ROS2=OFF: configure "
      "with Debian's cyclonedds-dev and cyclonedds-tools installed, "
      "scripts/install-deps.sh)"};
}

}  // namespace telear::drivers
