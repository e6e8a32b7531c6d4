#pragma once
// The stereo pairs of two ROS 1 camera topics as a vision::StereoSource: `telear vision-server
// --source ros --left TOPIC --right TOPIC` (docs/ros.md, "Cameras").
//
//   images       sensor_msgs/Image, or sensor_msgs/CompressedImage on a topic ending in
//                /compressed, converted to RGB8 (drivers/ros1/ros1_camera_link.hpp lists the
//                encodings)
//   pairing      left and right by header stamp, each other's nearest within the sync
//                tolerance (approximate time, drivers/ros1/stamp_pairing.hpp); the pairing
//                error (left stamp minus right stamp) is what the two eyes' capture times
//                differ by, and its mean and maximum are logged every stats period and at
//                the end
//   capture time each eye's header stamp on this machine's CLOCK_MONOTONIC
//                (drivers/ros1/ros_clock_offset.hpp)
//   calibration  from the cameras' camera_info (drivers/ros1/camera_info_calibration.hpp):
//                intrinsics, lens model, and the pose between the cameras where the two P
//                state a rectified pair; read once, at start
//
// Opening waits (up to startup_timeout_s) for the master, the first pairs (their size is the
// source's, and their stamps give the rate when fps is 0) and, with camera_info, both
// cameras' camera_info. capture() blocks until the next pair; after frame_timeout_s without
// one it fails, naming what is wrong (the master, a silent topic, images that cannot be
// converted, stamps further apart than the tolerance), and the vision pipeline retries.
//
// ROS types stay in the C++17 unit behind drivers/ros1/ros1_camera_link.hpp; this header has
// none. roscpp allows one node per process: the vision server's ROS source is its own.

#include <memory>
#include <string>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/vision/stereo_source.hpp"

namespace telear::drivers {

struct Ros1StereoSourceOptions {
  std::string master_uri;  // http://HOST:PORT; empty: $ROS_MASTER_URI
  std::string left_topic = "/stereo/left/image_raw";
  std::string right_topic = "/stereo/right/image_raw";
  double sync_tolerance_s = 0.02;  // the largest stamp difference of a pair
  bool camera_info = true;         // derive the calibration from camera_info
  double fps = 0.0;                // the nominal rate reported; 0: from the first pairs' stamps
  double startup_timeout_s = 5.0;
  double frame_timeout_s = 2.0;
  double stats_period_s = 10.0;  // how often the pairing's figures are logged
};

struct Ros1StereoSource {
  std::unique_ptr<vision::StereoSource> source;  // name() "ros"
  // A stereo camera file (telear/vision/camera_file.hpp) from camera_info, for GetCameraInfo;
  // empty without camera_info or when a camera is uncalibrated (a warning then says why).
  std::string calibration_yaml;
  std::vector<std::string> warnings;
};

// Errors: bad options, another ROS node in this process, no master, no frames or no pairs
// within startup_timeout_s (naming the topic), images of two sizes, a camera_info telear
// cannot represent (naming the topic and the field), or a build without ROS 1.
Result<Ros1StereoSource> open_ros1_stereo_source(const Ros1StereoSourceOptions& options);

// Whether this build has the ROS 1 source.
bool ros1_stereo_source_built();

}  // namespace telear::drivers
