#pragma once
// The stereo source a vision server streams, chosen by name as `telear vision-server --source`
// names it (docs/network.md, "Sources"):
//
//   sim        the simulated rig (telear/sim/sim_rig_source.hpp); with `robot_server`, the
//              arm in its video follows that robot server's state stream (a robot client
//              named "telear-vision-server", with `robot_token_file`'s token)
//   files      a pair of video files (telear/vision/video_file_source.hpp)
//   v4l2       two cameras (telear/vision/camera_source.hpp)
//   synthetic  generated frames at any size and rate (telear/vision/synthetic_source.hpp)
//   ros        two ROS 1 camera topics, `left` and `right` (telear/drivers/ros1_stereo_source.hpp,
//              docs/ros.md "Cameras"), with the calibration their camera_info states. It lives
//              in telear::drivers, which lab does not link: a program offers it by setting
//              `open_ros` (telear's vision-server does); without it "ros" is not a source.
//
// A size applies to files, v4l2 and synthetic; the rig file sets the simulated cameras' size,
// and the topics the ROS cameras', so a size given for sim or ros is ignored with a warning.

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "telear/core/image_size.hpp"
#include "telear/core/result.hpp"
#include "telear/net/robot_client.hpp"
#include "telear/vision/stereo_source.hpp"

namespace telear::lab {

struct VisionSource;

struct VisionSourceOptions {
  std::string kind = "sim";  // sim | files | v4l2 | synthetic | ros
  std::string rig;           // sim: the rig file; empty: the shipped rig
  std::string robot_server;  // sim: HOST:PORT of the robot server the arm follows
  std::string robot_token_file;
  std::string left, right;  // files; ros: the image topics
  int left_camera = 0;      // v4l2: device indices
  int right_camera = 1;
  double fps = 0.0;                     // 0: the source's default
  std::optional<core::ImageSize> size;  // none: the source's own
  int supersample = 2;                  // sim
  double noise = 1.0;                   // sim, grey levels
  bool frame_code = false;              // sim, synthetic: stamp the frame code (frame_code.hpp)
  std::string ros_master;               // ros: http://HOST:PORT; empty: $ROS_MASTER_URI
  double sync_tolerance_ms = 20.0;      // ros: the largest stamp difference of a pair
  bool camera_info = true;              // ros: the calibration from camera_info (no file given)
  // ros: opens the source (the program's, see above); fps 0 means measured from the stamps.
  std::function<Result<VisionSource>(const VisionSourceOptions&)> open_ros;
};

struct VisionSource {
  // The robot the simulated rig follows: the source reads it, so it must outlive the source
  // (keep this struct alive until the server that took `source` has stopped).
  std::unique_ptr<net::RobotClient> robot;
  std::unique_ptr<vision::StereoSource> source;
  // A stereo camera file's text the source knows itself (ros: from camera_info), for the
  // vision server's GetCameraInfo when no calibration file is given; empty: none.
  std::string calibration_yaml;
  std::vector<std::string> warnings;
};

// Errors (naming the field, not a command-line option): an unknown kind, a robot server for
// another source than sim, a missing left or right file (or topic), the rig, a file, a camera
// or a topic that cannot be opened (naming it), a token file.
Result<VisionSource> open_vision_source(const VisionSourceOptions& options);

}  // namespace telear::lab
