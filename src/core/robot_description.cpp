// load_robot_description: a shipped name, a robot file (YAML with `urdf:`), a DH table (YAML
// with `convention:`) or a URDF, into one RobotDescription (docs/robot-files.md). The robot
// file adds to the URDF what it does not hold: the tip, the gripper, named configurations,
// the body override and the marker mount.

#include "telear/core/robot_description.hpp"

#include "telear/core/resource_uri.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cassert>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "telear/core/angles.hpp"
#include "telear/core/companion_file.hpp"
#include "telear/core/robot_loader.hpp"
#include "telear/core/yaml_reader.hpp"
#include "urdf_description.hpp"

namespace telear::core {

bool RobotLink::moves_with_gripper() const {
  return std::any_of(steps.begin(), steps.end(),
                     [](const AttachmentStep& s) { return s.gripper_joint >= 0; });
}

double GripperJoint::value(double fraction) const {
  return multiplier * (closed + fraction * (open - closed)) + offset;
}

Eigen::Isometry3d GripperJoint::transform(double fraction) const {
  const double v = value(fraction);
  Eigen::Isometry3d Z = Eigen::Isometry3d::Identity();
  if (type == JointType::kPrismatic) {
    Z.translation().z() = v;
  } else {
    Z.linear() = Eigen::AngleAxisd(v, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  }
  return before * Z * after;
}

double Gripper::fraction(double opening_m) const {
  if (!(max_opening_m > 0.0) || !std::isfinite(opening_m)) return 0.0;
  return std::clamp(opening_m / max_opening_m, 0.0, 1.0);
}

const RobotLink* RobotDescription::link(const std::string& link_name) const {
  for (const RobotLink& l : links) {
    if (l.name == link_name) return &l;
  }
  return nullptr;
}

Eigen::Isometry3d RobotDescription::T_frame_link(std::size_t index, double gripper_fraction) const {
  assert(index < links.size());
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (const AttachmentStep& step : links[index].steps) {
    if (step.gripper_joint < 0) {
      T = T * step.fixed;
    } else if (gripper && static_cast<std::size_t>(step.gripper_joint) < gripper->joints.size()) {
      T = T *
          gripper->joints[static_cast<std::size_t>(step.gripper_joint)].transform(gripper_fraction);
    }
  }
  return T;
}

namespace {

namespace fs = std::filesystem;

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string absolute_from(const fs::path& base_dir, const std::string& path) {
  const fs::path p(path);
  return (p.is_absolute() ? p : base_dir / p).lexically_normal().string();
}

Result<std::string> scalar_string(const YAML::Node& node, const std::string& what) {
  if (!node.IsScalar() || node.Scalar().empty()) return Error{what + " must be a non-empty string"};
  return node.Scalar();
}

// The companion files of a DH table or a plain URDF (companion_file.hpp).
Status add_companions(RobotDescription& d, bool body, bool marker) {
  if (body && d.body_file.empty()) d.body_file = find_companion_file(*d.model, ".body.yaml");
  if (marker && !d.marker) {
    const std::string path = find_companion_file(*d.model, ".marker.yaml");
    if (!path.empty()) {
      auto mount = load_marker_mount_file(path);
      if (!mount) return mount.error();
      d.marker = *mount;
    }
  }
  return Status::Ok();
}

Result<RobotModelPtr> create_model(RobotModel::Description d) {
  auto model = RobotModel::create(std::move(d));
  if (!model) return model.error();
  return std::make_shared<const RobotModel>(std::move(model).value());
}

Result<RobotDescription> from_urdf_text(std::string text, const std::string& source,
                                        const std::string& tip) {
  auto urdf = describe_urdf(text, source, tip);
  if (!urdf) return urdf.error();
  RobotDescription d;
  d.name = urdf->model.name;
  d.source = source;
  d.urdf_text = std::move(text);
  d.root_link = urdf->root_link;
  d.tip_link = urdf->tip_link;
  d.links = std::move(urdf->links);
  auto model = create_model(std::move(urdf->model));
  if (!model) return model.error();
  d.model = *model;
  return d;
}

Result<RobotDescription> from_urdf(const std::string& path, const std::string& tip,
                                   bool companions) {
  auto text = read_urdf_text(path);
  if (!text) return text.error();
  auto d = from_urdf_text(std::move(text).value(), path, tip);
  if (!d) return d.error();
  d->urdf_path = path;
  if (Status s = add_companions(*d, companions, companions); !s) return s.error();
  return d;
}

Result<RobotDescription> from_dh_table(const std::string& path, const std::string& tip,
                                       bool companions) {
  if (!tip.empty()) {
    return Error{"robot file '" + path + "' is a DH table: it has no links, so no tip '" + tip +
                 "' can be chosen (a tip applies to URDF robots)"};
  }
  auto model = load_dh_yaml_file(path);
  if (!model) return model.error();
  RobotDescription d;
  d.model = std::make_shared<const RobotModel>(std::move(model).value());
  d.name = d.model->name();
  d.source = path;
  if (Status s = add_companions(d, companions, companions); !s) return s.error();
  return d;
}

// The robot file (docs/robot-files.md, "Robot file").
Result<RobotDescription> from_robot_file(const std::string& path, const YAML::Node& root,
                                         const std::string& spec_tip,
                                         const std::vector<std::string>& spec_package_paths,
                                         bool companions) {
  const std::string where = "robot file '" + path + "': ";
  const fs::path dir = fs::path(path).parent_path();
  static const std::vector<std::string> kKeys = {"name",
                                                 "urdf",
                                                 "package_paths",
                                                 "tip",
                                                 "gripper",
                                                 "named_configurations_deg",
                                                 "named_configurations_rad",
                                                 "body",
                                                 "marker",
                                                 "allowed_collisions"};
  for (const auto& entry : root) {
    const std::string key = entry.first.IsScalar() ? entry.first.Scalar() : "?";
    if (std::find(kKeys.begin(), kKeys.end(), key) == kKeys.end()) {
      std::string expected;
      for (const auto& k : kKeys) expected += (expected.empty() ? "" : ", ") + k;
      return Error{where + "unknown key '" + key + "' (expected " + expected + ")"};
    }
  }
  RobotDescription d;
  d.source = path;

  if (const YAML::Node paths = root["package_paths"]) {
    if (!paths.IsSequence()) return Error{where + "package_paths must be a list of directories"};
    for (std::size_t i = 0; i < paths.size(); ++i) {
      auto p = scalar_string(paths[i], where + "package_paths[" + std::to_string(i) + "]");
      if (!p) return p.error();
      d.package_paths.push_back(absolute_from(dir, *p));
    }
  }

  auto urdf_value = scalar_string(root["urdf"], where + "urdf");
  if (!urdf_value) return urdf_value.error();
  std::string urdf_path = *urdf_value;
  if (urdf_path.rfind("package://", 0) == 0) {
    // The same search as the URDF's meshes (core/resource_uri.hpp).
    ResourceSearchPaths search;
    search.package_paths = spec_package_paths;
    search.robot_package_paths = d.package_paths;
    search.ros_package_path = ros_package_path_from_environment();
    auto resolved = resolve_resource_uri(urdf_path, search, "urdf");
    if (!resolved) return Error{where + resolved.error().message};
    urdf_path = *resolved;
  } else {
    if (urdf_path.rfind("file://", 0) == 0) urdf_path = urdf_path.substr(7);
    urdf_path = absolute_from(dir, urdf_path);
  }
  std::error_code ec;
  if (!fs::is_regular_file(urdf_path, ec)) {
    return Error{where + "urdf: '" + urdf_path + "' does not exist"};
  }

  std::string tip = spec_tip;
  if (tip.empty() && root["tip"]) {
    auto t = scalar_string(root["tip"], where + "tip");
    if (!t) return t.error();
    tip = *t;
  }

  std::optional<RobotFileGripper> gripper;
  if (const YAML::Node g = root["gripper"]) {
    if (!g.IsMap())
      return Error{where + "gripper must be a map (joints, closed, open, max_opening_m)"};
    RobotFileGripper spec;
    spec.where = where;
    for (const auto& entry : g) {
      const std::string key = entry.first.IsScalar() ? entry.first.Scalar() : "?";
      if (key != "joints" && key != "closed" && key != "open" && key != "max_opening_m") {
        return Error{where + "gripper: unknown key '" + key +
                     "' (expected joints, closed, open, max_opening_m)"};
      }
    }
    if (!g["joints"] || !g["joints"].IsSequence() || g["joints"].size() == 0) {
      return Error{where + "gripper.joints must be a non-empty list of joint names"};
    }
    for (std::size_t i = 0; i < g["joints"].size(); ++i) {
      auto name =
          scalar_string(g["joints"][i], where + "gripper.joints[" + std::to_string(i) + "]");
      if (!name) return name.error();
      spec.joints.push_back(*name);
    }
    for (const char* key : {"closed", "open"}) {
      const std::string what = where + "gripper." + key;
      if (!g[key]) return Error{what + ": missing"};
      auto values = yaml_numbers(g[key], what);
      if (!values) return values.error();
      if (values->size() != spec.joints.size()) {
        return Error{what + " must be a list of " + std::to_string(spec.joints.size()) +
                     " numbers (one per gripper joint)"};
      }
      (std::string(key) == "closed" ? spec.closed : spec.open) = *values;
    }
    if (g["max_opening_m"]) {
      auto m = yaml_number(g["max_opening_m"], where + "gripper.max_opening_m");
      if (!m) return m.error();
      if (!(*m > 0.0)) return Error{where + "gripper.max_opening_m must be positive"};
      spec.max_opening_m = *m;
    }
    gripper = std::move(spec);
  }

  auto text = read_urdf_text(urdf_path);
  if (!text) return text.error();
  auto urdf = describe_urdf(*text, urdf_path, tip, gripper);
  if (!urdf) return urdf.error();
  RobotModel::Description& model = urdf->model;

  if (root["name"]) {
    auto n = scalar_string(root["name"], where + "name");
    if (!n) return n.error();
    model.name = *n;
  }
  // The model's source is the robot file, so that its companion files sit beside it.
  model.source = path;

  // Named configurations: added to the URDF's `zero`; one named `zero` replaces it.
  for (const char* key : {"named_configurations_deg", "named_configurations_rad"}) {
    const YAML::Node configs = root[key];
    if (!configs) continue;
    const bool degrees = std::string(key) == "named_configurations_deg";
    if (!configs.IsMap()) return Error{where + key + " must be a map name: [values]"};
    for (const auto& entry : configs) {
      const std::string name = entry.first.IsScalar() ? entry.first.Scalar() : "?";
      const std::string what = where + key + "." + name;
      auto values = yaml_numbers(entry.second, what);
      if (!values) return values.error();
      if (values->size() != model.joints.size()) {
        return Error{what + " must be a list of " + std::to_string(model.joints.size()) +
                     " numbers (one per chain joint)"};
      }
      Eigen::VectorXd q(static_cast<Eigen::Index>(values->size()));
      for (std::size_t i = 0; i < values->size(); ++i) {
        const bool revolute = model.joints[i].type == JointType::kRevolute;
        q[static_cast<Eigen::Index>(i)] =
            degrees && revolute ? radians_from_degrees((*values)[i]) : (*values)[i];
      }
      auto& named = model.named_configurations;
      named.erase(std::remove_if(named.begin(), named.end(),
                                 [&](const NamedConfiguration& c) { return c.name == name; }),
                  named.end());
      named.push_back({name, q});
    }
  }

  if (root["body"]) {
    auto b = scalar_string(root["body"], where + "body");
    if (!b) return b.error();
    d.body_file = absolute_from(dir, *b);
    if (!fs::is_regular_file(d.body_file, ec)) {
      return Error{where + "body: '" + d.body_file + "' does not exist"};
    }
  }
  if (const YAML::Node m = root["marker"]) {
    if (m.IsScalar()) {
      const std::string marker_path = absolute_from(dir, m.Scalar());
      auto mount = load_marker_mount_file(marker_path);
      if (!mount) return Error{where + "marker: " + mount.error().message};
      d.marker = *mount;
    } else {
      YAML::Emitter emitter;
      emitter << m;
      auto mount = parse_marker_mount_yaml(emitter.c_str(), where + "marker");
      if (!mount) return mount.error();
      d.marker = *mount;
    }
  }

  if (const YAML::Node acm = root["allowed_collisions"]) {
    const std::string what = where + "allowed_collisions";
    if (!acm.IsSequence()) return Error{what + ": must be a list of [link, link, reason]"};
    std::vector<AllowedCollisionEntry> entries;
    for (std::size_t i = 0; i < acm.size(); ++i) {
      const YAML::Node e = acm[i];
      const std::string at = what + "[" + std::to_string(i) + "]";
      if (!e.IsSequence() || e.size() < 2 || e.size() > 3) {
        return Error{at + ": must be [link, link] or [link, link, reason]"};
      }
      AllowedCollisionEntry entry;
      for (std::size_t k = 0; k < e.size(); ++k) {
        if (!e[k].IsScalar()) return Error{at + ": must be [link, link] or [link, link, reason]"};
      }
      entry.a = e[0].Scalar();
      entry.b = e[1].Scalar();
      if (e.size() == 3) entry.reason = e[2].Scalar();
      for (const std::string* link : {&entry.a, &entry.b}) {
        const bool known = std::any_of(urdf->links.begin(), urdf->links.end(),
                                       [&](const RobotLink& l) { return l.name == *link; });
        if (!known) return Error{at + ": '" + *link + "' is not a link of the URDF"};
      }
      static const std::vector<std::string> kReasons = {"adjacent", "always", "never", "constant",
                                                        "user"};
      if (std::find(kReasons.begin(), kReasons.end(), entry.reason) == kReasons.end()) {
        return Error{at + ": unknown reason '" + entry.reason +
                     "' (adjacent, always, never, constant or user)"};
      }
      entries.push_back(std::move(entry));
    }
    d.allowed_collisions = std::move(entries);
  }

  d.name = model.name;
  d.urdf_path = urdf_path;
  d.urdf_text = std::move(text).value();
  d.root_link = urdf->root_link;
  d.tip_link = urdf->tip_link;
  d.links = std::move(urdf->links);
  d.gripper = std::move(urdf->gripper);
  auto created = create_model(std::move(model));
  if (!created) return Error{where + created.error().message};
  d.model = *created;
  if (Status s = add_companions(d, companions, companions); !s) return s.error();
  return d;
}

Result<RobotDescription> load_robot_description_impl(const RobotSpec& spec, bool companions) {
  const std::string& name_or_path = spec.name_or_path;
  if (name_or_path.empty()) return Error{"no robot given: name one (e.g. puma560) or a file"};
  const bool looks_like_path = name_or_path.find('/') != std::string::npos ||
                               ends_with(name_or_path, ".yaml") ||
                               ends_with(name_or_path, ".yml") || ends_with(name_or_path, ".urdf");
  std::string path = name_or_path;
  if (!looks_like_path) {
    path = (fs::path(data_directory()) / "robots" / (name_or_path + ".yaml")).string();
    if (!fs::exists(path)) {
      return Error{"unknown robot '" + name_or_path + "': no " + path +
                   " (give a shipped name such as puma560, or a .yaml / .urdf file)"};
    }
  }
  if (!fs::exists(path)) return Error{"robot file '" + path + "' does not exist"};
  if (ends_with(path, ".urdf")) return from_urdf(path, spec.tip, companions);
  if (ends_with(path, ".yaml") || ends_with(path, ".yml")) {
    // A file that is not a YAML map, or has no `urdf:`, is the DH loader's to judge.
    auto root = load_yaml_file(path, "robot file '" + path + "': ");
    if (root && root->IsMap() && root.value()["urdf"]) {
      return catch_yaml_errors<RobotDescription>("robot file '" + path + "': ", [&] {
        return from_robot_file(path, *root, spec.tip, spec.package_paths, companions);
      });
    }
    return from_dh_table(path, spec.tip, companions);
  }
  return Error{"robot file '" + path + "': unknown format (expected .urdf, .yaml or .yml)"};
}

}  // namespace

Result<RobotDescription> load_robot_description(const RobotSpec& spec) {
  return load_robot_description_impl(spec, true);
}

Result<RobotModelPtr> load_robot(const RobotSpec& spec) {
  // The chain only: a malformed companion file does not stop a command that needs no marker.
  auto d = load_robot_description_impl(spec, false);
  if (!d) return d.error();
  return d->model;
}

Result<RobotModelPtr> load_robot(const std::string& name_or_path) {
  return load_robot(RobotSpec{name_or_path, ""});
}

std::string urdf_text_for_clients(const RobotDescription& description) {
  if (!description.urdf_text.empty()) return description.urdf_text;
  fs::path path = description.source;
  path.replace_extension(".urdf");
  std::ifstream in(path);
  if (!in) return "";
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

Result<RobotDescription> parse_urdf_description(const std::string& text, const std::string& source,
                                                const std::string& tip) {
  return from_urdf_text(text, source, tip);
}

}  // namespace telear::core
