// Parser of the arm body file (data/robots/NAME.body.yaml, docs/rendering.md). Keys carry
// their units (_m); colours are RGB in 0..1. Unknown keys are errors, so a typo does not
// silently give a default shape.

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "telear/core/arm_body.hpp"
#include "telear/core/yaml_reader.hpp"

namespace telear::core {
namespace {

constexpr int kMaxSegments = 1024;

float number(const YAML::Node& node, const std::string& what) {
  if (!node) throw YamlFieldError{what + " must be a number"};
  return static_cast<float>(number_or_throw(node, what, " "));
}

float positive_size(const YAML::Node& node, const std::string& what) {
  const float v = number(node, what);
  if (v <= 0.0f) throw YamlFieldError{what + " must be positive, got " + node.Scalar()};
  return v;
}

template <int N>
Eigen::Matrix<float, N, 1> vec(const YAML::Node& node, const std::string& what) {
  if (!node || !node.IsSequence() || node.size() != N) {
    throw YamlFieldError{what + " must be a list of " + std::to_string(N) + " numbers"};
  }
  Eigen::Matrix<float, N, 1> v;
  for (int i = 0; i < N; ++i) v[i] = number(node[i], what + "[" + std::to_string(i) + "]");
  return v;
}

Eigen::Vector3f direction(const YAML::Node& node, const std::string& what) {
  const Eigen::Vector3f v = vec<3>(node, what);
  if (v.norm() < 1e-9f) throw YamlFieldError{what + " must not be the zero vector"};
  return v.normalized();
}

Eigen::Vector3f colour(const YAML::Node& node, const std::string& what) {
  const Eigen::Vector3f c = vec<3>(node, what);
  if ((c.array() < 0.0f).any() || (c.array() > 1.0f).any()) {
    throw YamlFieldError{what + " must be RGB values in [0, 1]"};
  }
  return c;
}

int segments(const YAML::Node& node, const std::string& what) {
  const float v = number(node, what);
  if (v != std::floor(v) || v < kMinCylinderSegments || v > kMaxSegments) {
    throw YamlFieldError{what + " must be a whole number in [" +
                         std::to_string(kMinCylinderSegments) + ", " +
                         std::to_string(kMaxSegments) + "], got " + node.Scalar()};
  }
  return static_cast<int>(v);
}

ShapeSpec shape(const YAML::Node& node, const Eigen::Vector3f& default_colour,
                const std::string& what) {
  if (!node.IsMap()) throw YamlFieldError{what + " must be a map"};
  if (!node["type"]) throw YamlFieldError{what + ": missing 'type' (cylinder, prism or box)"};
  const std::string type = node["type"].Scalar();
  ShapeSpec s;
  s.colour = node["colour"] ? colour(node["colour"], what + ".colour") : default_colour;
  if (type == "cylinder" || type == "prism") {
    s.from = vec<3>(node["from_m"], what + ".from_m");
    s.to = vec<3>(node["to_m"], what + ".to_m");
    if ((s.to - s.from).norm() < 1e-6f) throw YamlFieldError{what + ": from_m and to_m coincide"};
  }
  if (type == "cylinder") {
    ok_or_throw(
        check_yaml_keys(node, {"type", "from_m", "to_m", "radius_m", "segments", "colour"}, what));
    s.kind = ShapeSpec::Kind::kCylinder;
    s.radius = positive_size(node["radius_m"], what + ".radius_m");
    if (node["segments"]) s.segments = segments(node["segments"], what + ".segments");
  } else if (type == "prism") {
    ok_or_throw(check_yaml_keys(
        node, {"type", "from_m", "to_m", "size_from_m", "size_to_m", "up", "colour"}, what));
    s.kind = ShapeSpec::Kind::kPrism;
    s.size_from = vec<2>(node["size_from_m"], what + ".size_from_m");
    s.size_to = node["size_to_m"] ? vec<2>(node["size_to_m"], what + ".size_to_m") : s.size_from;
    if ((s.size_from.array() <= 0.0f).any() || (s.size_to.array() <= 0.0f).any()) {
      throw YamlFieldError{what + ": prism sizes must be positive"};
    }
    s.up = node["up"] ? direction(node["up"], what + ".up") : Eigen::Vector3f::UnitY();
    const Eigen::Vector3f axis = (s.to - s.from).normalized();
    if (std::abs(axis.dot(s.up)) > 0.999f) {
      throw YamlFieldError{what + ": 'up' must not be parallel to the prism's axis"};
    }
  } else if (type == "box") {
    ok_or_throw(check_yaml_keys(node, {"type", "centre_m", "size_m", "colour"}, what));
    s.kind = ShapeSpec::Kind::kBox;
    s.centre = vec<3>(node["centre_m"], what + ".centre_m");
    s.size = vec<3>(node["size_m"], what + ".size_m");
    if ((s.size.array() <= 0.0f).any()) throw YamlFieldError{what + ".size_m must be positive"};
  } else {
    throw YamlFieldError{what + ": unknown type '" + type + "' (cylinder, prism or box)"};
  }
  return s;
}

GripperSpec gripper(const YAML::Node& node, int dof) {
  const std::string what = "gripper";
  if (!node.IsMap()) throw YamlFieldError{what + " must be a map"};
  ok_or_throw(check_yaml_keys(node,
                              {"link", "centre_m", "axis", "palm_centre_m", "palm_size_m",
                               "finger_size_m", "opening_m", "max_opening_m", "colour"},
                              what));
  GripperSpec g;
  const float link = number(node["link"], what + ".link");
  if (link != std::floor(link) || link < 1 || link > static_cast<float>(dof)) {
    throw YamlFieldError{what + ".link must be a link index in [1, " + std::to_string(dof) + "]"};
  }
  g.link = static_cast<int>(link);
  g.centre = vec<3>(node["centre_m"], what + ".centre_m");
  g.axis = direction(node["axis"], what + ".axis");
  g.palm_centre = vec<3>(node["palm_centre_m"], what + ".palm_centre_m");
  g.palm_size = vec<3>(node["palm_size_m"], what + ".palm_size_m");
  g.finger_size = vec<3>(node["finger_size_m"], what + ".finger_size_m");
  if ((g.palm_size.array() <= 0.0f).any() || (g.finger_size.array() <= 0.0f).any()) {
    throw YamlFieldError{what + ": palm and finger sizes must be positive"};
  }
  g.max_opening = positive_size(node["max_opening_m"], what + ".max_opening_m");
  g.opening = number(node["opening_m"], what + ".opening_m");
  if (g.opening < 0.0f || g.opening > g.max_opening) {
    throw YamlFieldError{what + ".opening_m must be in [0, max_opening_m]"};
  }
  if (node["colour"]) g.colour = colour(node["colour"], what + ".colour");
  return g;
}

BodyDescription parse_body_description(const YAML::Node& root, const std::string& source,
                                       const RobotModel& model) {
  if (!root.IsMap()) throw YamlFieldError{"the file must be a YAML map"};
  ok_or_throw(
      check_yaml_keys(root, {"robot", "frames", "segments", "colour", "links", "gripper"}, "body"));
  if (root["robot"] && root["robot"].Scalar() != model.name()) {
    throw YamlFieldError{"it describes robot '" + root["robot"].Scalar() + "', not '" +
                         model.name() + "'"};
  }
  const std::string frames = root["frames"] ? root["frames"].Scalar() : "model";
  if (frames != "model" && frames != "standard_dh") {
    throw YamlFieldError{"'frames' must be model or standard_dh, got '" + frames + "'"};
  }
  if (frames == "standard_dh" && !model.dh()) {
    throw YamlFieldError{"shapes are in standard DH frames but robot '" + model.name() + "' (" +
                         model.source() + ") has no DH table"};
  }
  BodyDescription d;
  d.source = source;
  if (root["segments"]) d.default_segments = segments(root["segments"], "segments");
  const Eigen::Vector3f default_colour =
      root["colour"] ? colour(root["colour"], "colour") : Eigen::Vector3f(0.7f, 0.7f, 0.72f);
  const int dof = model.dof();
  d.links.resize(static_cast<std::size_t>(dof) + 1);
  const YAML::Node links = root["links"];
  if (!links || !links.IsMap()) {
    throw YamlFieldError{"'links' must be a map of link index (0 = base .. " + std::to_string(dof) +
                         ") to a list of shapes"};
  }
  for (const auto& entry : links) {
    const std::string key = entry.first.Scalar();
    int index = -1;
    try {
      std::size_t used = 0;
      index = std::stoi(key, &used);
      if (used != key.size()) index = -1;
    } catch (const std::exception&) {
      index = -1;
    }
    if (index < 0 || index > dof) {
      throw YamlFieldError{"links: '" + key + "' is not a link index in [0, " +
                           std::to_string(dof) + "]"};
    }
    const std::string what = "links." + key;
    if (!entry.second.IsSequence()) throw YamlFieldError{what + " must be a list of shapes"};
    for (std::size_t k = 0; k < entry.second.size(); ++k) {
      d.links[static_cast<std::size_t>(index)].push_back(
          shape(entry.second[k], default_colour, what + "[" + std::to_string(k) + "]"));
    }
  }
  if (root["gripper"]) d.gripper = gripper(root["gripper"], dof);
  return d;
}

}  // namespace

Result<BodyDescription> parse_body_yaml(const std::string& text, const std::string& source,
                                        const RobotModel& model) {
  const std::string where = "body file '" + source + "': ";
  auto root = load_yaml(text, where);
  if (!root) return root.error();
  return catch_yaml_errors<BodyDescription>(
      where, [&] { return parse_body_description(*root, source, model); });
}

Result<BodyDescription> load_body_yaml_file(const std::string& path, const RobotModel& model) {
  std::ifstream in(path);
  if (!in) return Error{"cannot open body file '" + path + "'"};
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parse_body_yaml(buffer.str(), path, model);
}

Result<BodyDescription> body_description_for(const RobotModel& model) {
  const std::string path = find_body_file(model);
  if (path.empty()) return default_body_description(model);
  if (!model.dh()) {
    // A body file in DH frames does not fit a model with other link frames (the URDF of the
    // same arm): such a model gets the default body rather than misplaced shapes.
    // An unreadable file falls through: load_body_yaml_file reports it with its context.
    const auto root = load_yaml_file(path, "");
    if (root && root->IsMap() && (*root)["frames"] && (*root)["frames"].Scalar() == "standard_dh") {
      return default_body_description(model);
    }
  }
  return load_body_yaml_file(path, model);
}

}  // namespace telear::core
