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
//
// A size applies to files, v4l2 and synthetic; the rig file sets the simulated cameras' size,
// so a size given for sim is ignored with a warning.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "telear/core/image_size.hpp"
#include "telear/core/result.hpp"
#include "telear/net/robot_client.hpp"
#include "telear/vision/stereo_source.hpp"

namespace telear::lab {

struct VisionSourceOptions {
  std::string kind = "sim";  // sim | files | v4l2 | synthetic
  std::string rig;           // sim: the rig file; empty: the shipped rig
  std::string robot_server;  // sim: HOST:PORT of the robot server the arm follows
  std::string robot_token_file;
  std::string left, right;  // files
  int left_camera = 0;      // v4l2: device indices
  int right_camera = 1;
  double fps = 0.0;                     // 0: the source's default
  std::optional<core::ImageSize> size;  // none: the source's own
  int supersample = 2;                  // sim
  double noise = 1.0;                   // sim, grey levels
};

struct VisionSource {
  // The robot the simulated rig follows: the source reads it, so it must outlive the source
  // (keep this struct alive until the server that took `source` has stopped).
  std::unique_ptr<net::RobotClient> robot;
  std::unique_ptr<vision::StereoSource> source;
  std::vector<std::string> warnings;
};

// Errors (naming the field, not a command-line option): an unknown kind, a robot server for
// another source than sim, a missing left or right file, the rig, a file or a camera that
// cannot be opened (naming it), a token file.
Result<VisionSource> open_vision_source(const VisionSourceOptions& options);

}  // namespace telear::lab
