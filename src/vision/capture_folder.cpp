#include "telear/vision/capture_folder.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "telear/core/number_format.hpp"
#include "telear/core/yaml_reader.hpp"
#include "telear/vision/calibration_file.hpp"
#include "telear/vision/image_file.hpp"

namespace telear::vision {
namespace {

namespace fs = std::filesystem;

Eigen::VectorXd joint_vector(const YAML::Node& node, const std::string& what) {
  if (!node) throw core::YamlFieldError{what + ": missing (joint values, rad)"};
  const std::vector<double> values = core::numbers_or_throw(node, what);
  if (values.empty()) throw core::YamlFieldError{what + ": empty"};
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

std::int64_t whole_number(const YAML::Node& node, const std::string& what) {
  if (!node) throw core::YamlFieldError{what + ": missing"};
  const double value = core::number_or_throw(node, what);
  if (value != std::floor(value) || std::fabs(value) > 9.0e18) {
    throw core::YamlFieldError{what + ": must be a whole number, got " + node.Scalar()};
  }
  return static_cast<std::int64_t>(value);
}

std::string text(const YAML::Node& node, const std::string& what) {
  if (!node || node.IsNull()) return {};
  if (!node.IsScalar()) throw core::YamlFieldError{what + ": must be a string"};
  return node.Scalar();
}

// A path recorded in the manifest must stay inside the folder: relative, no "..".
std::string relative_path(const YAML::Node& node, const std::string& what) {
  const std::string path = text(node, what);
  if (path.empty())
    throw core::YamlFieldError{what + ": missing (an image path relative to the folder)"};
  const fs::path p(path);
  if (p.is_absolute())
    throw core::YamlFieldError{what + ": '" + path + "' must be relative to the folder"};
  for (const fs::path& part : p) {
    if (part == "..")
      throw core::YamlFieldError{what + ": '" + path + "' leaves the folder ('..')"};
  }
  return path;
}

std::string joint_list(const Eigen::VectorXd& q) {
  std::string list = "[";
  for (Eigen::Index j = 0; j < q.size(); ++j) {
    list += (j == 0 ? "" : ", ") + core::format_number(q[j], "%.17g");
  }
  return list + "]";
}

std::string pose_name(std::size_t p) {
  return "poses[" + std::to_string(p) + "]";
}

}  // namespace

Result<CaptureSet> parse_capture_manifest(const std::string& manifest, const std::string& source,
                                          const CaptureReadOptions& options) {
  const std::string where = "capture '" + source + "': ";
  const auto loaded = core::load_yaml(manifest, where);
  if (!loaded) return loaded.error();
  return core::catch_yaml_errors<CaptureSet>(where, [&] {
    CaptureSet capture;
    const YAML::Node& root = *loaded;
    if (!root.IsMap())
      throw core::YamlFieldError{"the manifest must be a YAML map (docs/capture.md)"};
    const YAML::Node version = root["telear_capture"];
    if (!version) {
      throw core::YamlFieldError{
          "telear_capture: missing (the format version, 1); is this a capture.yaml?"};
    }
    if (whole_number(version, "telear_capture") != 1) {
      throw core::YamlFieldError{"telear_capture: unsupported version " + version.Scalar() +
                                 " (this telear reads 1)"};
    }
    capture.robot = text(root["robot"], "robot");
    capture.tip_link = text(root["tip_link"], "tip_link");
    capture.target = text(root["target"], "target");
    if (root["cameras"]) capture.camera_file = relative_path(root["cameras"], "cameras");
    const YAML::Node poses = root["poses"];
    if (!poses || !poses.IsSequence() || poses.size() == 0) {
      throw core::YamlFieldError{"poses: missing or empty; capture at least one pose"};
    }
    for (std::size_t p = 0; p < poses.size(); ++p) {
      const std::string at = pose_name(p);
      const YAML::Node entry = poses[p];
      if (!entry.IsMap()) throw core::YamlFieldError{at + ": must be a map with q, frames"};
      CapturedPose pose;
      pose.q = joint_vector(entry["q"], at + ".q");
      pose.q_commanded =
          entry["q_commanded"] ? joint_vector(entry["q_commanded"], at + ".q_commanded") : pose.q;
      if (pose.q_commanded.size() != pose.q.size()) {
        throw core::YamlFieldError{at + ".q_commanded: " + std::to_string(pose.q_commanded.size()) +
                                   " joint values, but q has " + std::to_string(pose.q.size())};
      }
      if (p > 0 && pose.q.size() != capture.poses[0].q.size()) {
        throw core::YamlFieldError{at + ".q: " + std::to_string(pose.q.size()) +
                                   " joint values, but poses[0] has " +
                                   std::to_string(capture.poses[0].q.size())};
      }
      pose.joint_time_ns =
          entry["joint_time_ns"] ? whole_number(entry["joint_time_ns"], at + ".joint_time_ns") : 0;
      const YAML::Node frames = entry["frames"];
      if (!frames || !frames.IsSequence() || frames.size() == 0) {
        throw core::YamlFieldError{at +
                                   ".frames: missing or empty; recapture the pose or remove it"};
      }
      for (std::size_t f = 0; f < frames.size(); ++f) {
        const std::string fat = at + ".frames[" + std::to_string(f) + "]";
        const YAML::Node node = frames[f];
        if (!node.IsMap()) throw core::YamlFieldError{fat + ": must be a map with left, right"};
        CapturedFrame frame;
        const std::int64_t id =
            node["frame_id"] ? whole_number(node["frame_id"], fat + ".frame_id") : 0;
        if (id < 0) throw core::YamlFieldError{fat + ".frame_id: must not be negative"};
        frame.frame_id = static_cast<std::uint64_t>(id);
        frame.left_time_ns =
            node["left_time_ns"] ? whole_number(node["left_time_ns"], fat + ".left_time_ns") : 0;
        frame.right_time_ns =
            node["right_time_ns"] ? whole_number(node["right_time_ns"], fat + ".right_time_ns") : 0;
        const std::int64_t skew = std::llabs(frame.left_time_ns - frame.right_time_ns);
        if (skew > options.max_sync_skew_ns) {
          throw core::YamlFieldError{fat + ": unsynchronized: the eyes were exposed " +
                                     core::format_number(skew * 1e-6, "%.1f") +
                                     " ms apart (at most " +
                                     core::format_number(options.max_sync_skew_ns * 1e-6, "%.1f") +
                                     " ms); synchronize the cameras or recapture the pose"};
        }
        frame.left_image = relative_path(node["left"], fat + ".left");
        frame.right_image = relative_path(node["right"], fat + ".right");
        pose.frames.push_back(std::move(frame));
      }
      capture.poses.push_back(std::move(pose));
    }
    return capture;
  });
}

std::string capture_manifest_yaml(const CaptureSet& capture) {
  std::string yaml =
      "# telear capture (docs/capture.md): joint states and stereo images at each pose\n"
      "telear_capture: 1\n";
  yaml += "robot: \"" + capture.robot + "\"\n";
  if (!capture.tip_link.empty()) yaml += "tip_link: \"" + capture.tip_link + "\"\n";
  if (!capture.target.empty()) yaml += "target: \"" + capture.target + "\"\n";
  if (!capture.camera_file.empty()) yaml += "cameras: \"" + capture.camera_file + "\"\n";
  yaml += "poses:\n";
  for (const CapturedPose& pose : capture.poses) {
    yaml += "  - q_commanded: " + joint_list(pose.q_commanded) + "\n";
    yaml += "    q: " + joint_list(pose.q) + "\n";
    yaml += "    joint_time_ns: " + std::to_string(pose.joint_time_ns) + "\n";
    yaml += "    frames:\n";
    for (const CapturedFrame& frame : pose.frames) {
      yaml += "      - frame_id: " + std::to_string(frame.frame_id) + "\n";
      yaml += "        left_time_ns: " + std::to_string(frame.left_time_ns) + "\n";
      yaml += "        right_time_ns: " + std::to_string(frame.right_time_ns) + "\n";
      yaml += "        left: \"" + frame.left_image + "\"\n";
      yaml += "        right: \"" + frame.right_image + "\"\n";
    }
  }
  return yaml;
}

Result<CaptureSet> load_capture_folder(const std::string& directory,
                                       const CaptureReadOptions& options) {
  const fs::path folder(directory);
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) {
    return Error{"capture '" + directory +
                 "': not a folder (give the folder telear capture wrote)"};
  }
  const fs::path manifest = folder / "capture.yaml";
  std::ifstream in(manifest, std::ios::binary);
  if (!in) {
    return Error{"capture '" + directory +
                 "': capture.yaml missing or unreadable; is this a capture folder?"};
  }
  std::ostringstream content;
  content << in.rdbuf();
  auto capture = parse_capture_manifest(content.str(), directory, options);
  if (!capture) return capture;
  const std::string where = "capture '" + directory + "': ";
  if (!capture->camera_file.empty() && !fs::is_regular_file(folder / capture->camera_file, ec)) {
    return Error{where + "cameras: '" + capture->camera_file + "' missing"};
  }
  for (std::size_t p = 0; p < capture->poses.size(); ++p) {
    const auto& frames = capture->poses[p].frames;
    for (std::size_t f = 0; f < frames.size(); ++f) {
      for (const bool left : {true, false}) {
        const std::string& image = left ? frames[f].left_image : frames[f].right_image;
        if (!fs::is_regular_file(folder / image, ec)) {
          return Error{where + pose_name(p) + ".frames[" + std::to_string(f) + "]." +
                       (left ? "left" : "right") + ": image '" + image +
                       "' missing; recapture the pose or remove it from capture.yaml"};
        }
      }
    }
  }
  return capture;
}

Status write_capture_manifest(const CaptureSet& capture, const std::string& directory) {
  return write_files_atomically(
      {{(fs::path(directory) / "capture.yaml").string(), capture_manifest_yaml(capture)}});
}

std::string captured_image_path(int pose, int frame, bool left) {
  char folder[32];
  std::snprintf(folder, sizeof folder, "pose_%03d", pose);
  return std::string(folder) + (left ? "/left_" : "/right_") + std::to_string(frame) + ".png";
}

Status write_captured_images(const std::string& directory, const CapturedFrame& frame,
                             const cv::Mat& left, const cv::Mat& right) {
  for (const bool is_left : {true, false}) {
    const fs::path path = fs::path(directory) / (is_left ? frame.left_image : frame.right_image);
    std::error_code ec;
    fs::create_directories(path.parent_path(), ec);
    if (ec) return Error{"cannot create '" + path.parent_path().string() + "': " + ec.message()};
    const cv::Mat& image = is_left ? left : right;
    if (image.empty()) return Error{"cannot write '" + path.string() + "': empty image"};
    if (Status written = write_png_file(path.string(), image); !written) return written;
  }
  return Status::Ok();
}

Result<StereoImages> read_captured_images(const std::string& directory,
                                          const CapturedFrame& frame) {
  StereoImages images;
  for (const bool is_left : {true, false}) {
    const fs::path path = fs::path(directory) / (is_left ? frame.left_image : frame.right_image);
    auto image = read_image_file(path.string(), ImageFileMode::kUnchanged);
    if (!image) {
      return Error{"capture image '" + path.string() +
                   "' cannot be read (missing or not an image)"};
    }
    (is_left ? images.left : images.right) = std::move(*image);
  }
  return images;
}

}  // namespace telear::vision
