#include "telear/core/yaml_reader.hpp"

#include "telear/core/pose.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

namespace telear::core {

std::string describe_yaml_error(const YAML::Exception& error) {
  if (error.mark.is_null()) return "not valid YAML: " + error.msg;
  return "not valid YAML at line " + std::to_string(error.mark.line + 1) + ": " + error.msg;
}

Result<YAML::Node> load_yaml(const std::string& text, const std::string& where) {
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    return Error{where + describe_yaml_error(e)};
  }
}

Result<YAML::Node> load_yaml_file(const std::string& path, const std::string& where) {
  std::ifstream in(path);
  if (!in) return Error{where + "cannot be read"};
  std::stringstream text;
  text << in.rdbuf();
  return load_yaml(text.str(), where);
}

Result<double> yaml_number(const YAML::Node& node, const std::string& what,
                           const std::string& separator) {
  const std::string field = what + separator;
  if (!node.IsScalar()) return Error{field + "must be a number"};
  double value = 0.0;
  try {
    value = node.as<double>();
  } catch (const YAML::Exception&) {
    return Error{field + "must be a number, got '" + node.Scalar() + "'"};
  }
  if (!std::isfinite(value)) return Error{field + "must be finite, got " + node.Scalar()};
  return value;
}

Result<std::vector<double>> yaml_numbers(const YAML::Node& node, const std::string& what) {
  if (!node.IsSequence()) return Error{what + ": must be a list of numbers"};
  std::vector<double> values;
  for (std::size_t i = 0; i < node.size(); ++i) {
    auto value = yaml_number(node[i], what + "[" + std::to_string(i) + "]");
    if (!value) return value.error();
    values.push_back(*value);
  }
  return values;
}

Result<Eigen::Vector3d> yaml_vector3(const YAML::Node& node, const std::string& what) {
  if (!node.IsSequence() || node.size() != 3) return Error{what + " must be a list of 3 numbers"};
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) {
    auto value = yaml_number(node[i], what + "[" + std::to_string(i) + "]");
    if (!value) return value.error();
    v[i] = *value;
  }
  return v;
}

Result<Eigen::Isometry3d> yaml_pose(const YAML::Node& node, const std::string& what) {
  if (!node.IsMap()) return Error{what + " must be a map {xyz: [x, y, z], rpy: [r, p, y]}"};
  for (const auto& entry : node) {
    const std::string key = entry.first.Scalar();
    if (key != "xyz" && key != "rpy") {
      return Error{what + ": unknown key '" + key + "' (expected xyz, rpy)"};
    }
  }
  if (!node["xyz"]) return Error{what + ".xyz: missing"};
  auto xyz = yaml_vector3(node["xyz"], what + ".xyz");
  if (!xyz) return xyz.error();
  Eigen::Vector3d rpy = Eigen::Vector3d::Zero();
  if (node["rpy"]) {
    auto value = yaml_vector3(node["rpy"], what + ".rpy");
    if (!value) return value.error();
    rpy = *value;
  }
  return pose_from_xyz_rpy(*xyz, rpy);
}

Status check_yaml_keys(const YAML::Node& node, const std::set<std::string>& allowed,
                       const std::string& what) {
  for (const auto& entry : node) {
    const std::string key = entry.first.Scalar();
    if (allowed.count(key) == 0) {
      std::string list;
      for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
      return Error{(what.empty() ? "" : what + ": ") + "unknown key '" + key + "' (expected " +
                   list + ")"};
    }
  }
  return Status::Ok();
}

void ok_or_throw(const Status& status) {
  if (!status) throw YamlFieldError{status.error().message};
}

double number_or_throw(const YAML::Node& node, const std::string& what,
                       const std::string& separator) {
  return value_or_throw(yaml_number(node, what, separator));
}

std::vector<double> numbers_or_throw(const YAML::Node& node, const std::string& what) {
  return value_or_throw(yaml_numbers(node, what));
}

}  // namespace telear::core
