#include "telear/core/marker_mount.hpp"

#include <yaml-cpp/yaml.h>

#include <fstream>
#include <set>
#include <sstream>

#include "telear/core/companion_file.hpp"
#include "telear/core/pose.hpp"
#include "telear/core/yaml_reader.hpp"

namespace telear::core {
namespace {

// Parsing throws this inside this file only; the entry points turn it into a Result.
struct ParseError {
  std::string message;
};

double number(const YAML::Node& node, const std::string& what) {
  auto value = yaml_number(node, what);
  if (!value) throw ParseError{value.error().message};
  return *value;
}

constexpr int kDictionarySize = 50;  // DICT_4X4_50

Eigen::Vector3d vector3(const YAML::Node& node, const std::string& what) {
  if (!node.IsSequence() || node.size() != 3) {
    throw ParseError{what + " must be a list of 3 numbers"};
  }
  return {number(node[0], what + "[0]"), number(node[1], what + "[1]"),
          number(node[2], what + "[2]")};
}

}  // namespace

std::array<Eigen::Vector3d, 4> MarkerMount::corners_flange() const {
  const double h = side_m / 2.0;
  const std::array<Eigen::Vector3d, 4> corners_marker = {
      Eigen::Vector3d(-h, h, 0), Eigen::Vector3d(h, h, 0), Eigen::Vector3d(h, -h, 0),
      Eigen::Vector3d(-h, -h, 0)};
  std::array<Eigen::Vector3d, 4> corners;
  for (int k = 0; k < 4; ++k) corners[k] = T_flange_marker * corners_marker[k];
  return corners;
}

Result<MarkerMount> parse_marker_mount_yaml(const std::string& text, const std::string& source) {
  MarkerMount mount;
  try {
    const YAML::Node root = YAML::Load(text);
    if (!root.IsMap()) return Error{source + ": not a marker file (dictionary, id, side_m, pose)"};
    const std::set<std::string> allowed = {"dictionary", "id", "side_m", "pose_in_flange"};
    for (const auto& entry : root) {
      if (!allowed.count(entry.first.Scalar())) {
        return Error{source + ": unknown key '" + entry.first.Scalar() +
                     "' (expected dictionary, id, side_m, pose_in_flange)"};
      }
    }
    if (root["dictionary"]) mount.dictionary = root["dictionary"].Scalar();
    if (mount.dictionary != "DICT_4X4_50") {
      return Error{source + ": dictionary '" + mount.dictionary +
                   "' is not supported (DICT_4X4_50)"};
    }
    if (!root["id"]) return Error{source + ": id: missing (0..49)"};
    const double id = number(root["id"], "id");
    if (id != static_cast<int>(id) || id < 0 || id >= kDictionarySize) {
      return Error{source + ": id " + root["id"].Scalar() +
                   " is outside DICT_4X4_50's range 0..49"};
    }
    mount.id = static_cast<int>(id);
    if (!root["side_m"]) return Error{source + ": side_m: missing (m)"};
    mount.side_m = number(root["side_m"], "side_m");
    if (!(mount.side_m > 0.0)) {
      return Error{source + ": side_m must be positive, got " + root["side_m"].Scalar()};
    }
    const YAML::Node pose = root["pose_in_flange"];
    if (!pose || !pose.IsMap() || !pose["xyz"]) {
      return Error{source + ": pose_in_flange: missing ({xyz: [x, y, z], rpy: [r, p, y]})"};
    }
    const Eigen::Vector3d xyz = vector3(pose["xyz"], "pose_in_flange.xyz");
    const Eigen::Vector3d rpy =
        pose["rpy"] ? vector3(pose["rpy"], "pose_in_flange.rpy") : Eigen::Vector3d::Zero();
    mount.T_flange_marker = pose_from_xyz_rpy(xyz, rpy);
  } catch (const ParseError& e) {
    return Error{source + ": " + e.message};
  } catch (const YAML::Exception& e) {
    return Error{source + ": " + describe_yaml_error(e)};
  }
  return mount;
}

Result<MarkerMount> load_marker_mount_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) return Error{"cannot read the marker file " + path};
  std::stringstream text;
  text << in.rdbuf();
  return parse_marker_mount_yaml(text.str(), path);
}

Result<MarkerMount> marker_mount_for(const RobotModel& model) {
  const std::string path = find_companion_file(model, ".marker.yaml");
  if (path.empty()) {
    return Error{"robot '" + model.name() + "' has no marker file (" + model.name() +
                 ".marker.yaml beside the robot's file or in " + companion_directory() + ")"};
  }
  return load_marker_mount_file(path);
}

}  // namespace telear::core
