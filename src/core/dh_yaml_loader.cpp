// Parser of telear's DH robot table (docs/robot-files.md). Keys carry their units
// (_m, _deg, _rad, _deg_s, ...); angles are converted to radians here, once.

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>

#include "telear/core/angles.hpp"

#include "telear/core/pose.hpp"
#include "telear/core/robot_loader.hpp"
#include "telear/core/yaml_reader.hpp"

namespace telear::core {
namespace {

std::vector<double> numbers(const YAML::Node& node, const std::string& what, size_t count) {
  if (!node.IsSequence() || node.size() != count) {
    throw YamlFieldError{what + " must be a list of " + std::to_string(count) + " numbers"};
  }
  std::vector<double> values;
  for (size_t i = 0; i < count; ++i) {
    values.push_back(number_or_throw(node[i], what + "[" + std::to_string(i) + "]", " "));
  }
  return values;
}

// Reads `base`_deg or `base`_rad as radians; nullopt when neither is given.
std::optional<double> angle(const YAML::Node& map, const std::string& base,
                            const std::string& what) {
  const YAML::Node deg = map[base + "_deg"];
  const YAML::Node rad = map[base + "_rad"];
  if (deg && rad)
    throw YamlFieldError{what + ": give " + base + "_deg or " + base + "_rad, not both"};
  if (deg) return radians_from_degrees(number_or_throw(deg, what + "." + base + "_deg", " "));
  if (rad) return number_or_throw(rad, what + "." + base + "_rad", " ");
  return std::nullopt;
}

// Reads `base`_m; 0 when absent (a DH length left out is zero).
double length(const YAML::Node& map, const std::string& base, const std::string& what) {
  const YAML::Node m = map[base + "_m"];
  if (!m) return 0.0;
  return number_or_throw(m, what + "." + base + "_m", " ");
}

// Angle pairs and rates: key_deg{suffix} or key_rad{suffix}, as a list of `count`.
std::optional<std::vector<double>> angles(const YAML::Node& map, const std::string& base,
                                          const std::string& suffix, const std::string& what,
                                          size_t count) {
  const std::string deg_key = base + "_deg" + suffix;
  const std::string rad_key = base + "_rad" + suffix;
  const YAML::Node deg = map[deg_key];
  const YAML::Node rad = map[rad_key];
  if (deg && rad)
    throw YamlFieldError{what + ": give " + deg_key + " or " + rad_key + ", not both"};
  if (!deg && !rad) return std::nullopt;
  std::vector<double> v = numbers(deg ? deg : rad, what + "." + (deg ? deg_key : rad_key), count);
  if (deg) {
    for (double& x : v) x = radians_from_degrees(x);
  }
  return v;
}

Eigen::Isometry3d transform(const YAML::Node& node, const std::string& what) {
  if (!node.IsMap()) throw YamlFieldError{what + " must be a map with xyz_m and rpy_deg/rpy_rad"};
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();
  if (node["xyz_m"]) {
    const auto v = numbers(node["xyz_m"], what + ".xyz_m", 3);
    xyz = {v[0], v[1], v[2]};
  }
  Eigen::Vector3d rpy = Eigen::Vector3d::Zero();
  if (auto v = angles(node, "rpy", "", what, 3)) rpy = {(*v)[0], (*v)[1], (*v)[2]};
  return pose_from_xyz_rpy(xyz, rpy);
}

RobotModel::Description parse_dh_description(const YAML::Node& root, const std::string& source) {
  if (!root.IsMap()) throw YamlFieldError{"the file must be a YAML map"};
  RobotModel::Description d;
  d.source = source;
  if (!root["name"] || !root["name"].IsScalar()) throw YamlFieldError{"missing 'name'"};
  d.name = root["name"].Scalar();
  const YAML::Node convention = root["convention"];
  if (!convention || convention.Scalar() != "standard_dh") {
    throw YamlFieldError{"'convention' must be standard_dh (the only DH form supported)"};
  }
  const YAML::Node joints = root["joints"];
  if (!joints || !joints.IsSequence() || joints.size() == 0) {
    throw YamlFieldError{"'joints' must be a non-empty list"};
  }
  std::vector<DhRow> rows;
  std::vector<std::string> names;
  std::vector<JointLimits> limits;
  for (size_t i = 0; i < joints.size(); ++i) {
    const YAML::Node j = joints[i];
    const std::string what = "joints[" + std::to_string(i) + "]";
    if (!j.IsMap()) throw YamlFieldError{what + " must be a map"};
    if (j["type"] && j["type"].Scalar() != "revolute") {
      throw YamlFieldError{what + ": only revolute DH joints are supported, got '" +
                           j["type"].Scalar() + "'"};
    }
    names.push_back(j["name"] ? j["name"].Scalar() : "joint" + std::to_string(i + 1));
    DhRow row;
    row.d = length(j, "d", what);
    row.a = length(j, "a", what);
    row.alpha = angle(j, "alpha", what).value_or(0.0);
    row.offset = angle(j, "offset", what).value_or(0.0);
    rows.push_back(row);
    JointLimits l;
    const auto range = angles(j, "limits", "", what, 2);
    if (!range) throw YamlFieldError{what + ": missing limits_deg or limits_rad"};
    l.lower = (*range)[0];
    l.upper = (*range)[1];
    const YAML::Node v_deg = j["max_velocity_deg_s"];
    const YAML::Node v_rad = j["max_velocity_rad_s"];
    const YAML::Node a_deg = j["max_acceleration_deg_s2"];
    const YAML::Node a_rad = j["max_acceleration_rad_s2"];
    if (!v_deg && !v_rad) throw YamlFieldError{what + ": missing max_velocity_deg_s or _rad_s"};
    if (!a_deg && !a_rad)
      throw YamlFieldError{what + ": missing max_acceleration_deg_s2 or _rad_s2"};
    l.max_velocity =
        v_deg ? radians_from_degrees(number_or_throw(v_deg, what + ".max_velocity_deg_s", " "))
              : number_or_throw(v_rad, what + ".max_velocity_rad_s", " ");
    l.max_acceleration =
        a_deg ? radians_from_degrees(number_or_throw(a_deg, what + ".max_acceleration_deg_s2", " "))
              : number_or_throw(a_rad, what + ".max_acceleration_rad_s2", " ");
    limits.push_back(l);
  }
  d.joints = joints_from_dh(rows, names, limits);
  d.dh = rows;
  if (root["tool"]) d.T_flange_tool = transform(root["tool"], "tool");
  for (const char* key : {"named_configurations_deg", "named_configurations_rad"}) {
    const YAML::Node configs = root[key];
    if (!configs) continue;
    if (!configs.IsMap())
      throw YamlFieldError{std::string(key) + " must be a map of name: [values]"};
    const bool degrees = std::string(key).find("_deg") != std::string::npos;
    for (const auto& entry : configs) {
      const std::string name = entry.first.Scalar();
      const auto v = numbers(entry.second, std::string(key) + "." + name, joints.size());
      NamedConfiguration c{name, Eigen::VectorXd(static_cast<Eigen::Index>(v.size()))};
      for (size_t k = 0; k < v.size(); ++k) {
        c.q[static_cast<Eigen::Index>(k)] = degrees ? radians_from_degrees(v[k]) : v[k];
      }
      d.named_configurations.push_back(std::move(c));
    }
  }
  return d;
}

}  // namespace

Result<RobotModel> parse_dh_yaml(const std::string& text, const std::string& source) {
  const std::string where = "robot file '" + source + "': ";
  auto root = load_yaml(text, where);
  if (!root) return root.error();
  return catch_yaml_errors<RobotModel>(
      where, [&] { return RobotModel::create(parse_dh_description(*root, source)); });
}

Result<RobotModel> load_dh_yaml_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) return Error{"cannot open robot file '" + path + "'"};
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parse_dh_yaml(buffer.str(), path);
}

}  // namespace telear::core
