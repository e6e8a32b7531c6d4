#pragma once
// The ROS side of the ROS 1 stereo source (telear/drivers/ros1_stereo_source.hpp): one roscpp
// node that subscribes to a left and a right camera's images and their camera_info, converts
// each image to RGB8, pairs left and right by header stamp (stamp_pairing.hpp) and hands the
// newest pair over. Everything ROS stays in ros1_camera_link.cpp, a C++17 unit (ROS 1 message
// headers do not compile as C++20): this header uses the standard library only.
//
// Topics. An image topic whose name ends in "/compressed" carries sensor_msgs/CompressedImage
// (image_transport's compressed transport: JPEG or PNG), any other sensor_msgs/Image. The
// camera_info topic is image_transport's: "camera_info" beside the image topic, i.e.
// /stereo/left/image_raw and /stereo/left/image_raw/compressed both have
// /stereo/left/camera_info.
//
// Images. Raw encodings rgb8, bgr8, rgba8, bgra8, mono8, mono16 and the four 8-bit Bayer
// patterns; compressed ones whatever OpenCV's imdecode reads. Anything else is counted and
// reported (EyeHealth::last_error), never paired.
//
// Time. A message's capture time on this machine's CLOCK_MONOTONIC is its receipt time less
// its age, ROS time at receipt minus the header stamp (ROS time is the wall clock, or /clock
// under use_sim_time): so the pipeline's latency starts at the camera, and the left-right
// difference of capture times is the stamps' difference. A message without a stamp is
// stamped at receipt; a stamp ahead of this machine's ROS clock (clock skew between
// machines) is taken as the receipt time. Each case is logged once.
//
// Health and reconnection, as ros1_link.hpp: a monitor asks the master for its pid every
// 100 ms; the subscriptions exist only while it answers, and are made again when a restarted
// master is back.
//
// One node per process: roscpp's node is process-wide (ros::init once, ros::shutdown once).
// start() refuses when a ROS node was already initialised in this process (roscpp's own
// ros::isInitialized(), which the robot driver's link sets too), so a camera link never
// silently shares the robot link's node, master and name. The vision server and the robot
// server are separate processes, each with its own node.

#include <array>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace telear::drivers::ros1 {

struct CameraLinkOptions {
  std::string master_uri;  // http://HOST:PORT; empty: $ROS_MASTER_URI
  // An anonymous name (a suffix is added): two vision servers on one master do not evict
  // each other, as two nodes of the same name would.
  std::string node_name = "telear_vision_server";
  std::string left_topic, right_topic;  // image topics
  double sync_tolerance_s = 0.02;       // the largest stamp difference of a pair
};

// The camera_info topic beside an image topic (image_transport's rule).
std::string camera_info_topic(const std::string& image_topic);
// Whether an image topic carries sensor_msgs/CompressedImage (its name ends in /compressed).
bool is_compressed_topic(const std::string& image_topic);

// A sensor_msgs/CameraInfo, copied out of ROS.
struct CameraInfoFields {
  std::string topic;
  std::string frame_id;
  int width = 0, height = 0;
  std::string distortion_model;
  std::vector<double> D;
  std::array<double, 9> K{}, R{};
  std::array<double, 12> P{};
  int binning_x = 0, binning_y = 0;
  int roi_x_offset = 0, roi_y_offset = 0, roi_width = 0, roi_height = 0;
};

struct EyeFrame {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // RGB8, width x height x 3, top row first, no padding
  std::string encoding;           // as received: "bgr8", "jpeg", ...
  std::int64_t stamp_ns = 0;      // header stamp, ROS time
  std::int64_t capture_ns = 0;    // the stamp on this machine's CLOCK_MONOTONIC
};

struct StereoPair {
  std::uint64_t number = 0;  // 1, 2, 3 ... per pair made
  EyeFrame left, right;
  std::int64_t pairing_error_ns() const { return left.stamp_ns - right.stamp_ns; }
};

struct EyeHealth {
  std::uint64_t received = 0;        // messages received
  std::uint64_t unconvertible = 0;   // of them, not converted to RGB8 (last_error says why)
  std::uint64_t unpaired = 0;        // converted, but dropped by the pairing
  std::int64_t last_receipt_ns = 0;  // CLOCK_MONOTONIC of the latest message; 0: none yet
  std::int64_t last_stamp_ns = 0;    // its stamp
  std::string last_error;
};

struct CameraLinkHealth {
  bool master = false;  // the master answered the last check
  std::string master_uri;
  EyeHealth left, right;
  std::uint64_t pairs = 0;
};

class CameraLink {
 public:
  using LogHandler = std::function<void(const std::string&)>;

  // Starts the node and its monitor; the master need not be up yet. Fails (message in
  // *error) on an invalid option, or when a ROS node already exists in this process.
  static std::unique_ptr<CameraLink> start(const CameraLinkOptions& options, LogHandler log,
                                           std::string* error);
  ~CameraLink();  // shuts the node down
  CameraLink(const CameraLink&) = delete;
  CameraLink& operator=(const CameraLink&) = delete;

  // The newest pair numbered above `after`, waiting up to `timeout` for one; nullopt on timeout.
  // Older pairs that were not taken are gone (latest wins: the numbers say how many).
  std::optional<StereoPair> next_pair(std::uint64_t after, std::chrono::nanoseconds timeout);
  // The latest camera_info of the left or right camera, once one arrived.
  std::optional<CameraInfoFields> camera_info(bool right) const;
  CameraLinkHealth health() const;

 private:
  class Node;
  explicit CameraLink(std::unique_ptr<Node> node);
  std::unique_ptr<Node> node_;
};

}  // namespace telear::drivers::ros1
