// The ROS 1 stereo source's entry points in a build without ROS 1 (TELEAR_WITH_ROS1=OFF).
#include "telear/drivers/ros1_stereo_source.hpp"

namespace telear::drivers {

bool ros1_stereo_source_built() {
  return false;
}

Result<Ros1StereoSource> open_ros1_stereo_source(const Ros1StereoSourceOptions&) {
  return Error{
      "this telear was built without the ROS 1 camera source (TELEAR_WITH_ROS1=OFF: "
      "configure with Debian's ROS 1 packages installed, scripts/install-deps.sh)"};
}

}  // namespace telear::drivers
