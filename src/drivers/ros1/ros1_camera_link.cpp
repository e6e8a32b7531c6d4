// C++17: ROS 1 headers (see ros1_camera_link.hpp).
#include "drivers/ros1/ros1_camera_link.hpp"
#include "drivers/ros1/ros_clock_offset.hpp"

#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/CompressedImage.h>
#include <sensor_msgs/Image.h>
#include <stb_image.h>
#include <time.h>

#include <atomic>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <opencv2/imgproc.hpp>
#include <thread>
#include <utility>

#include "drivers/ros1/stamp_pairing.hpp"

namespace telear::drivers::ros1 {
namespace {

std::atomic<bool> g_camera_link_started{false};

constexpr auto kMonitorPeriod = std::chrono::milliseconds(100);
constexpr char kCompressedSuffix[] = "/compressed";

std::string milliseconds(std::int64_t ns) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f ms", static_cast<double>(ns) * 1e-6);
  return text;
}

// OpenCV names a Bayer pattern by the second row's second and third pixels, ROS by the first
// two rows' first two: ROS rggb is OpenCV's BG (cv_bridge's table).
int bayer_code(const std::string& encoding) {
  if (encoding == "bayer_rggb8") return cv::COLOR_BayerBG2RGB;
  if (encoding == "bayer_bggr8") return cv::COLOR_BayerRG2RGB;
  if (encoding == "bayer_gbrg8") return cv::COLOR_BayerGR2RGB;
  if (encoding == "bayer_grbg8") return cv::COLOR_BayerGB2RGB;
  return -1;
}

// sensor_msgs/Image -> RGB8; the error (empty: none) says what is wrong with the message.
std::string convert_image(const sensor_msgs::Image& m, EyeFrame& out) {
  const std::string& e = m.encoding;
  const int code = bayer_code(e);
  std::size_t pixel_bytes = 0;
  if (e == "rgb8" || e == "bgr8") {
    pixel_bytes = 3;
  } else if (e == "rgba8" || e == "bgra8") {
    pixel_bytes = 4;
  } else if (e == "mono8" || code >= 0) {
    pixel_bytes = 1;
  } else if (e == "mono16") {
    pixel_bytes = 2;
  } else {
    return "encoding '" + e +
           "' is not supported (rgb8, bgr8, rgba8, bgra8, mono8, mono16, bayer_rggb8, "
           "bayer_bggr8, bayer_gbrg8, bayer_grbg8; or a compressed topic)";
  }
  const std::size_t width = m.width, height = m.height;
  if (width == 0 || height == 0 || width > 16384 || height > 16384) {
    return "image size " + std::to_string(width) + "x" + std::to_string(height) +
           " is outside 1..16384";
  }
  if (m.step < width * pixel_bytes || m.data.size() < m.step * height) {
    return "step " + std::to_string(m.step) + " and " + std::to_string(m.data.size()) +
           " data bytes are too few for " + std::to_string(width) + "x" + std::to_string(height) +
           " " + e;
  }
  out.width = static_cast<int>(width);
  out.height = static_cast<int>(height);
  out.encoding = e;
  out.rgb.resize(width * height * 3);
  if (code >= 0) {
    const cv::Mat mosaic(out.height, out.width, CV_8UC1, const_cast<std::uint8_t*>(m.data.data()),
                         m.step);
    cv::Mat rgb(out.height, out.width, CV_8UC3, out.rgb.data());
    cv::cvtColor(mosaic, rgb, code);
    return {};
  }
  // mono16: the more significant byte (a view, not a measurement).
  const std::size_t high = m.is_bigendian ? 0 : 1;
  for (std::size_t y = 0; y < height; ++y) {
    const std::uint8_t* in = m.data.data() + y * m.step;
    std::uint8_t* o = out.rgb.data() + y * width * 3;
    if (e == "rgb8") {
      std::memcpy(o, in, width * 3);
      continue;
    }
    for (std::size_t x = 0; x < width; ++x, o += 3) {
      const std::uint8_t* p = in + x * pixel_bytes;
      if (e == "bgr8" || e == "bgra8") {
        o[0] = p[2], o[1] = p[1], o[2] = p[0];
      } else if (e == "rgba8") {
        o[0] = p[0], o[1] = p[1], o[2] = p[2];
      } else {
        const std::uint8_t grey = pixel_bytes == 2 ? p[high] : p[0];
        o[0] = o[1] = o[2] = grey;
      }
    }
  }
  return {};
}

// sensor_msgs/CompressedImage (image_transport's compressed transport: JPEG or PNG) -> RGB8.
std::string convert_compressed(const sensor_msgs::CompressedImage& m, EyeFrame& out) {
  if (m.format.find("compressedDepth") != std::string::npos) {
    return "format '" + m.format + "' is a depth image, not a camera's";
  }
  if (m.data.empty()) return "an empty " + m.format + " image";
  // stb_image (as telear's image files): OpenCV's imgcodecs would load ~140 shared libraries
  // (GDAL, Poppler, ...) at every start of every program that links the drivers.
  int width = 0, height = 0, channels = 0;
  stbi_uc* rgb = stbi_load_from_memory(m.data.data(), static_cast<int>(m.data.size()), &width,
                                       &height, &channels, 3);
  if (rgb == nullptr) {
    return "cannot decode the '" + m.format + "' image (" + std::to_string(m.data.size()) +
           " bytes): " + stbi_failure_reason();
  }
  out.width = width;
  out.height = height;
  out.encoding = m.format;
  out.rgb.assign(rgb, rgb + static_cast<std::size_t>(width) * height * 3);
  stbi_image_free(rgb);
  return {};
}

CameraInfoFields camera_info_fields(const sensor_msgs::CameraInfo& m, const std::string& topic) {
  CameraInfoFields f;
  f.topic = topic;
  f.frame_id = m.header.frame_id;
  f.width = static_cast<int>(m.width);
  f.height = static_cast<int>(m.height);
  f.distortion_model = m.distortion_model;
  f.D = m.D;
  for (std::size_t i = 0; i < 9; ++i) f.K[i] = m.K[i], f.R[i] = m.R[i];
  for (std::size_t i = 0; i < 12; ++i) f.P[i] = m.P[i];
  f.binning_x = static_cast<int>(m.binning_x);
  f.binning_y = static_cast<int>(m.binning_y);
  f.roi_x_offset = static_cast<int>(m.roi.x_offset);
  f.roi_y_offset = static_cast<int>(m.roi.y_offset);
  f.roi_width = static_cast<int>(m.roi.width);
  f.roi_height = static_cast<int>(m.roi.height);
  return f;
}

bool is_ros_name(const std::string& name) {
  return !name.empty() && name.find_first_of(" \t\n") == std::string::npos;
}

}  // namespace

bool is_compressed_topic(const std::string& image_topic) {
  const std::size_t n = sizeof kCompressedSuffix - 1;
  return image_topic.size() > n &&
         image_topic.compare(image_topic.size() - n, n, kCompressedSuffix) == 0;
}

std::string camera_info_topic(const std::string& image_topic) {
  std::string base = image_topic;
  if (is_compressed_topic(base)) base.resize(base.size() - (sizeof kCompressedSuffix - 1));
  const std::size_t slash = base.rfind('/');
  return (slash == std::string::npos ? std::string() : base.substr(0, slash + 1)) + "camera_info";
}

class CameraLink::Node {
 public:
  Node(CameraLinkOptions options, LogHandler log)
      : options_(std::move(options)),
        log_(std::move(log)),
        topics_{options_.left_topic, options_.right_topic},
        info_topics_{camera_info_topic(options_.left_topic),
                     camera_info_topic(options_.right_topic)},
        pairing_(static_cast<std::int64_t>(std::llround(options_.sync_tolerance_s * 1e9))) {}

  void start() {
    handle_ = std::make_unique<ros::NodeHandle>();
    spinner_ = std::make_unique<ros::AsyncSpinner>(2);
    spinner_->start();
    monitor_ = std::thread([this] { monitor(); });
  }

  ~Node() {
    {
      std::lock_guard lock(pair_mutex_);
      stopping_ = true;
    }
    pair_ready_.notify_all();
    if (monitor_.joinable()) monitor_.join();
    {
      std::lock_guard lock(subscriptions_mutex_);
      unregister_locked();
    }
    if (spinner_) spinner_->stop();
    ros::shutdown();
  }

  std::optional<StereoPair> next_pair(std::uint64_t after, std::chrono::nanoseconds timeout) {
    std::unique_lock lock(pair_mutex_);
    pair_ready_.wait_for(lock, timeout,
                         [&] { return stopping_ || (newest_ && newest_->number > after); });
    if (!newest_ || newest_->number <= after) return std::nullopt;
    std::optional<StereoPair> pair = std::move(newest_);
    newest_.reset();
    return pair;
  }

  std::optional<CameraInfoFields> camera_info(bool right) const {
    std::lock_guard lock(health_mutex_);
    return info_[right ? 1 : 0];
  }

  CameraLinkHealth health() const {
    CameraLinkHealth health;
    {
      std::lock_guard lock(health_mutex_);
      health.left = eyes_[0];
      health.right = eyes_[1];
    }
    {
      std::lock_guard lock(pair_mutex_);
      health.left.unpaired = pairing_.dropped(false);
      health.right.unpaired = pairing_.dropped(true);
      health.pairs = pairs_;
    }
    health.master = master_;
    health.master_uri = ros::master::getURI();
    return health;
  }

 private:
  void monitor() {
    bool said_waiting = false;
    std::unique_lock stop_lock(pair_mutex_);
    while (!stopping_) {
      stop_lock.unlock();
      const bool master = ros::master::check();
      {
        std::lock_guard lock(subscriptions_mutex_);
        if (master && !registered_) {
          register_locked();
          log_("connected to the ROS master at " + ros::master::getURI() + ": subscribed to " +
               topics_[0] + ", " + topics_[1] + " and their camera_info");
          said_waiting = false;
        } else if (!master && registered_) {
          unregister_locked();
          log_("lost the ROS master at " + ros::master::getURI() + ": no frames until it is back");
        } else if (!master && !said_waiting) {
          log_("waiting for the ROS master at " + ros::master::getURI());
          said_waiting = true;
        }
      }
      master_ = master;
      stop_lock.lock();
      pair_ready_.wait_for(stop_lock, kMonitorPeriod, [this] { return stopping_; });
    }
  }

  void register_locked() {
    const auto hints = ros::TransportHints().tcpNoDelay();
    for (int eye = 0; eye < 2; ++eye) {
      const bool right = eye == 1;
      // A short queue: a callback slower than the camera for long skips frames, it never falls
      // far behind; a stall of a few frames (a loaded machine) loses none, nor so a pair.
      if (is_compressed_topic(topics_[eye])) {
        images_[eye] = handle_->subscribe<sensor_msgs::CompressedImage>(
            topics_[eye], 4,
            [this, right](const sensor_msgs::CompressedImage::ConstPtr& m) {
              const Receipt receipt = now();
              EyeFrame frame;
              const std::string error = convert_compressed(*m, frame);
              on_frame(right, m->header.stamp, receipt, std::move(frame), error);
            },
            ros::VoidConstPtr(), hints);
      } else {
        images_[eye] = handle_->subscribe<sensor_msgs::Image>(
            topics_[eye], 4,
            [this, right](const sensor_msgs::Image::ConstPtr& m) {
              const Receipt receipt = now();
              EyeFrame frame;
              const std::string error = convert_image(*m, frame);
              on_frame(right, m->header.stamp, receipt, std::move(frame), error);
            },
            ros::VoidConstPtr(), hints);
      }
      infos_[eye] = handle_->subscribe<sensor_msgs::CameraInfo>(
          info_topics_[eye], 1,
          [this, eye](const sensor_msgs::CameraInfo::ConstPtr& m) {
            CameraInfoFields fields = camera_info_fields(*m, info_topics_[eye]);
            std::lock_guard lock(health_mutex_);
            info_[eye] = std::move(fields);
          },
          ros::VoidConstPtr(), hints);
    }
    registered_ = true;
  }

  void unregister_locked() {
    for (int eye = 0; eye < 2; ++eye) {
      images_[eye].shutdown();
      infos_[eye].shutdown();
    }
    registered_ = false;
  }

  using Receipt = RosClockOffset::Reading;
  Receipt now() { return clock_offset_.read(); }

  void on_frame(bool right, const ros::Time& stamp, const Receipt& receipt, EyeFrame frame,
                const std::string& error) {
    const int eye = right ? 1 : 0;
    const std::string& topic = topics_[eye];
    // Each warning once per topic.
    if (stamp.isZero() && !warned_no_stamp_[eye].exchange(true)) {
      log_(topic + " has no header stamps: its images are paired and timed by their receipt");
    }
    frame.stamp_ns = stamp.isZero() ? receipt.ros_ns : static_cast<std::int64_t>(stamp.toNSec());
    if (frame.stamp_ns > receipt.ros_ns && !warned_future_[eye].exchange(true)) {
      log_("stamps on " + topic + " are " + milliseconds(frame.stamp_ns - receipt.ros_ns) +
           " ahead of this machine's ROS clock (the camera's machine and this one are not "
           "synchronised: chrony, NTP?): capture times are taken at receipt");
    }
    frame.capture_ns = RosClockOffset::capture_ns(frame.stamp_ns, receipt);
    {
      std::lock_guard lock(health_mutex_);
      EyeHealth& health = eyes_[eye];
      ++health.received;
      health.last_receipt_ns = receipt.monotonic_ns;
      health.last_stamp_ns = frame.stamp_ns;
      if (!error.empty()) {
        ++health.unconvertible;
        const std::string message = topic + ": " + error;
        if (message != health.last_error) log_(message);
        health.last_error = message;
        return;
      }
    }
    const std::int64_t stamp_ns = frame.stamp_ns;
    {
      std::lock_guard lock(pair_mutex_);
      for (auto& made : pairing_.add(right, stamp_ns, std::move(frame))) {
        StereoPair pair;
        pair.number = ++pairs_;
        pair.left = std::move(made.left);
        pair.right = std::move(made.right);
        newest_ = std::move(pair);
      }
    }
    pair_ready_.notify_all();
  }

  CameraLinkOptions options_;
  LogHandler log_;
  const std::string topics_[2];
  const std::string info_topics_[2];

  std::unique_ptr<ros::NodeHandle> handle_;
  std::unique_ptr<ros::AsyncSpinner> spinner_;

  std::mutex subscriptions_mutex_;  // the registrations below
  bool registered_ = false;
  ros::Subscriber images_[2], infos_[2];

  mutable std::mutex health_mutex_;  // eyes_, info_
  EyeHealth eyes_[2];
  std::optional<CameraInfoFields> info_[2];

  mutable std::mutex pair_mutex_;  // pairing_, pairs_, newest_, stopping_
  std::condition_variable pair_ready_;
  StampPairing<EyeFrame> pairing_;
  std::uint64_t pairs_ = 0;
  std::optional<StereoPair> newest_;
  bool stopping_ = false;

  std::atomic<bool> master_{false};
  std::atomic<bool> warned_no_stamp_[2] = {false, false};
  std::atomic<bool> warned_future_[2] = {false, false};
  RosClockOffset clock_offset_;
  std::thread monitor_;
};

std::unique_ptr<CameraLink> CameraLink::start(const CameraLinkOptions& options, LogHandler log,
                                              std::string* error) {
  std::string master_uri = options.master_uri;
  if (master_uri.empty()) {
    const char* environment = std::getenv("ROS_MASTER_URI");
    if (environment != nullptr) master_uri = environment;
  }
  if (master_uri.empty()) {
    *error = "no ROS master: give --ros-master http://HOST:PORT or set ROS_MASTER_URI";
    return nullptr;
  }
  if (master_uri.rfind("http://", 0) != 0) {
    *error = "the ROS master URI must look like http://HOST:PORT, got '" + master_uri + "'";
    return nullptr;
  }
  for (const auto& [what, name] :
       {std::pair{"--left", options.left_topic}, std::pair{"--right", options.right_topic}}) {
    if (!is_ros_name(name)) {
      *error = std::string(what) + " must be a ROS image topic, got '" + name + "'";
      return nullptr;
    }
  }
  if (options.left_topic == options.right_topic) {
    *error = "--left and --right name the same topic, " + options.left_topic;
    return nullptr;
  }
  if (!(options.sync_tolerance_s >= 0.0 && options.sync_tolerance_s <= 1.0)) {
    *error = "the sync tolerance must be within 0 .. 1000 ms";
    return nullptr;
  }
  // roscpp's flag covers a node started by any unit of this process (the robot link's too).
  if (ros::isInitialized() || g_camera_link_started.exchange(true)) {
    *error =
        "a ROS 1 node was already started in this process (roscpp allows one node per "
        "process): run the vision server in a process of its own";
    return nullptr;
  }
  ros::M_string remappings{{"__master", master_uri}};
  ros::init(remappings, options.node_name,
            ros::init_options::NoSigintHandler | ros::init_options::NoRosout |
                ros::init_options::AnonymousName);
  // A subscription with a master that went away gives up after this instead of blocking the
  // monitor forever; the monitor tries again on its next round.
  ros::master::setRetryTimeout(ros::WallDuration(1.0));
  auto node = std::make_unique<Node>(options, std::move(log));
  node->start();
  return std::unique_ptr<CameraLink>(new CameraLink(std::move(node)));
}

CameraLink::CameraLink(std::unique_ptr<Node> node) : node_(std::move(node)) {}
CameraLink::~CameraLink() = default;

std::optional<StereoPair> CameraLink::next_pair(std::uint64_t after,
                                                std::chrono::nanoseconds timeout) {
  return node_->next_pair(after, timeout);
}

std::optional<CameraInfoFields> CameraLink::camera_info(bool right) const {
  return node_->camera_info(right);
}

CameraLinkHealth CameraLink::health() const {
  return node_->health();
}

}  // namespace telear::drivers::ros1
