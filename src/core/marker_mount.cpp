#include "telear/core/marker_mount.hpp"

#include <yaml-cpp/yaml.h>

#include <set>

#include "telear/core/companion_file.hpp"
#include "telear/core/yaml_reader.hpp"

namespace telear::core {
namespace {

constexpr int kDictionarySize = 50;  // DICT_4X4_50

Result<MarkerMount> parse_marker_mount(const YAML::Node& root, const std::string& source) {
  if (!root.IsMap()) return Error{source + ": not a marker file (dictionary, id, side_m, pose)"};
  const std::set<std::string> allowed = {"dictionary", "id", "side_m", "pose_in_flange"};
  for (const auto& entry : root) {
    if (!allowed.count(entry.first.Scalar())) {
      return Error{source + ": unknown key '" + entry.first.Scalar() +
                   "' (expected dictionary, id, side_m, pose_in_flange)"};
    }
  }
  MarkerMount mount;
  if (root["dictionary"]) mount.dictionary = root["dictionary"].Scalar();
  if (mount.dictionary != "DICT_4X4_50") {
    return Error{source + ": dictionary '" + mount.dictionary + "' is not supported (DICT_4X4_50)"};
  }
  if (!root["id"]) return Error{source + ": id: missing (0..49)"};
  auto id = yaml_number(root["id"], "id");
  if (!id) return Error{source + ": " + id.error().message};
  if (*id != static_cast<int>(*id) || *id < 0 || *id >= kDictionarySize) {
    return Error{source + ": id " + root["id"].Scalar() + " is outside DICT_4X4_50's range 0..49"};
  }
  mount.id = static_cast<int>(*id);
  if (!root["side_m"]) return Error{source + ": side_m: missing (m)"};
  auto side = yaml_number(root["side_m"], "side_m");
  if (!side) return Error{source + ": " + side.error().message};
  if (!(*side > 0.0)) {
    return Error{source + ": side_m must be positive, got " + root["side_m"].Scalar()};
  }
  mount.side_m = *side;
  if (!root["pose_in_flange"]) {
    return Error{source + ": pose_in_flange: missing ({xyz: [x, y, z], rpy: [r, p, y]})"};
  }
  auto pose = yaml_pose(root["pose_in_flange"], "pose_in_flange");
  if (!pose) return Error{source + ": " + pose.error().message};
  mount.T_flange_marker = *pose;
  return mount;
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
  auto root = load_yaml(text, source + ": ");
  if (!root) return root.error();
  return parse_marker_mount(*root, source);
}

Result<MarkerMount> load_marker_mount_file(const std::string& path) {
  auto root = load_yaml_file(path, "marker file " + path + ": ");
  if (!root) return root.error();
  return parse_marker_mount(*root, path);
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
