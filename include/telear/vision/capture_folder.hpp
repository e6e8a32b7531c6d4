#pragma once
// A capture folder: what `telear capture` recorded at each robot pose for registration (and
// what `telear register --captures DIR` reads back), docs/capture.md. One folder per session:
//
//   DIR/capture.yaml                 the manifest below
//   DIR/cameras.yaml                 the stereo camera file the vision server reported
//                                    (optional; `register --rig` can give another)
//   DIR/pose_000/left_0.png          lossless images, both eyes, several frames per pose
//   DIR/pose_000/right_0.png
//   ...
//
// Manifest (YAML):
//
//   telear_capture: 1                # format version (required, = 1)
//   robot: puma560                   # the robot's name as GetInfo reported it
//   tip_link: ""                     # optional, informational
//   target: "aruco:DICT_4X4_50:0:0.1" # the target spec the poses were chosen for (optional)
//   cameras: cameras.yaml            # optional, relative to the folder
//   poses:
//     - q_commanded: [..]            # rad, where the arm was sent
//       q: [..]                      # rad, the measured joint state at rest
//       joint_time_ns: 1234          # the robot state's capture time (robot server clock)
//       frames:                      # >= 1 synchronized stereo frames at rest
//         - frame_id: 17             # the vision server's frame number
//           left_time_ns: 1230       # capture times of each eye (vision server clock)
//           right_time_ns: 1230
//           left: pose_000/left_0.png   # relative to the folder, no '..'
//           right: pose_000/right_0.png
//
// Checks on reading: the version, every pose with a q of the same size as the first, finite
// values, at least one frame per pose, image paths inside the folder; load_capture_folder()
// also checks that every image exists. A stereo frame whose eyes were exposed more than
// max_sync_skew_ns apart is refused as unsynchronized. Every error names the folder, the
// pose and the frame, and says what to do.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "telear/core/result.hpp"

namespace telear::vision {

struct CapturedFrame {
  std::uint64_t frame_id = 0;
  std::int64_t left_time_ns = 0;
  std::int64_t right_time_ns = 0;
  std::string left_image;   // relative to the capture folder
  std::string right_image;  // relative to the capture folder
};

struct CapturedPose {
  Eigen::VectorXd q_commanded;     // rad
  Eigen::VectorXd q;               // rad, measured at rest
  std::int64_t joint_time_ns = 0;  // robot server clock
  std::vector<CapturedFrame> frames;
};

struct CaptureSet {
  std::string robot;
  std::string tip_link;
  std::string target;       // target spec, informational
  std::string camera_file;  // relative to the folder; empty: none recorded
  std::vector<CapturedPose> poses;
};

struct CaptureReadOptions {
  // Eyes exposed further apart than this are not one stereo frame (a hardware-synchronized
  // pair is within microseconds; two free-running USB cameras at 30 fps within ~17 ms).
  std::int64_t max_sync_skew_ns = 5'000'000;
};

// The manifest text; `source` names it in errors ("capture 'DIR': poses[3].frames[0].left: ...").
Result<CaptureSet> parse_capture_manifest(const std::string& text, const std::string& source,
                                          const CaptureReadOptions& options = {});
std::string capture_manifest_yaml(const CaptureSet& capture);

// DIR/capture.yaml read and checked, images included (they must exist and be readable files).
Result<CaptureSet> load_capture_folder(const std::string& directory,
                                       const CaptureReadOptions& options = {});

// Writes DIR/capture.yaml atomically (the folder must exist).
Status write_capture_manifest(const CaptureSet& capture, const std::string& directory);

// The relative image paths of frame `frame` at pose `pose`: "pose_007/left_2.png".
std::string captured_image_path(int pose, int frame, bool left);

// Writes one stereo frame's images as PNG (lossless) under DIR, creating the pose folder.
Status write_captured_images(const std::string& directory, const CapturedFrame& frame,
                             const cv::Mat& left, const cv::Mat& right);

struct StereoImages {
  cv::Mat left;
  cv::Mat right;
};
// Reads one frame's images (colour as stored); errors name the file.
Result<StereoImages> read_captured_images(const std::string& directory, const CapturedFrame& frame);

}  // namespace telear::vision
