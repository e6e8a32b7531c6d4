#include "telear/sim/stereo_rig.hpp"

#include "telear/core/robot_loader.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "telear/core/yaml_reader.hpp"
#include "telear/vision/registration_target.hpp"

namespace telear::sim {
namespace {

namespace fs = std::filesystem;

// Errors carry "rig file '<source>': <field>: <why>".
struct Context {
  std::string source;
  Error error(const std::string& field, const std::string& why) const {
    return Error{"rig file '" + source + "': " + field + ": " + why};
  }
};

Result<std::vector<double>> read_numbers(const Context& ctx, const YAML::Node& node,
                                         const std::string& field, std::size_t count) {
  if (!node || !node.IsSequence() || node.size() != count) {
    return ctx.error(field, "expected a list of " + std::to_string(count) + " numbers");
  }
  std::vector<double> values;
  for (std::size_t i = 0; i < count; ++i) {
    try {
      values.push_back(node[i].as<double>());
    } catch (const YAML::Exception&) {
      return ctx.error(field, "element " + std::to_string(i) + " is not a number");
    }
    if (!std::isfinite(values.back())) {
      return ctx.error(field, "element " + std::to_string(i) + " is not finite");
    }
  }
  return values;
}

Result<Eigen::Vector3d> read_vector3(const Context& ctx, const YAML::Node& node,
                                     const std::string& field) {
  auto values = read_numbers(ctx, node, field, 3);
  if (!values) return values.error();
  return Eigen::Vector3d((*values)[0], (*values)[1], (*values)[2]);
}

Result<vision::CameraModel> read_camera(const Context& ctx, const YAML::Node& node,
                                        const std::string& field) {
  if (!node || !node.IsMap()) return ctx.error(field, "missing (a map of the camera's values)");
  for (const auto& entry : node) {
    const auto key = entry.first.as<std::string>();
    if (key != "image_size" && key != "fc" && key != "cc" && key != "alpha_c" &&
        key != "distortion_model" && key != "kc") {
      return ctx.error(field + "." + key,
                       "unknown key (expected image_size, fc, cc, alpha_c, distortion_model, kc)");
    }
  }
  vision::CameraModel camera;
  auto size = read_numbers(ctx, node["image_size"], field + ".image_size", 2);
  if (!size) return size.error();
  if ((*size)[0] != std::floor((*size)[0]) || (*size)[1] != std::floor((*size)[1])) {
    return ctx.error(field + ".image_size", "width and height must be whole numbers");
  }
  camera.width = static_cast<int>((*size)[0]);
  camera.height = static_cast<int>((*size)[1]);
  auto fc = read_numbers(ctx, node["fc"], field + ".fc", 2);
  if (!fc) return fc.error();
  auto cc = read_numbers(ctx, node["cc"], field + ".cc", 2);
  if (!cc) return cc.error();
  camera.fx = (*fc)[0];
  camera.fy = (*fc)[1];
  camera.cx = (*cc)[0];
  camera.cy = (*cc)[1];
  if (node["alpha_c"]) {
    try {
      camera.alpha_c = node["alpha_c"].as<double>();
    } catch (const YAML::Exception&) {
      return ctx.error(field + ".alpha_c", "must be a number");
    }
  }
  // distortion_model: a ROS name (default plumb_bob); kc: that model's D vector (5, 8 or 4
  // numbers; default all zero).
  vision::DistortionModel model = vision::DistortionModel::plumb_bob;
  if (node["distortion_model"]) {
    std::string name;
    try {
      name = node["distortion_model"].as<std::string>();
    } catch (const YAML::Exception&) {
      return ctx.error(field + ".distortion_model", "must be a name");
    }
    auto parsed = vision::parse_distortion_model(name);
    if (!parsed) return ctx.error(field + ".distortion_model", parsed.error().message);
    model = *parsed;
  }
  camera.kc.model = model;
  if (node["kc"]) {
    const std::size_t count = vision::distortion_coefficient_count(model);
    auto kc = read_numbers(ctx, node["kc"], field + ".kc", count);
    if (!kc) {
      return ctx.error(field + ".kc", "expected a list of " + std::to_string(count) +
                                          " numbers (the " + vision::distortion_model_name(model) +
                                          " D vector)");
    }
    camera.kc = vision::Distortion::from_coefficients(model, *kc).value();
  }
  if (auto valid = vision::validate_camera(camera); !valid) {
    return ctx.error(field, valid.error().message);
  }
  return camera;
}

// workspace_error: {xyz, rpy, objects: {NAME: {xyz, rpy}}} (see the header).
Result<WorkspaceError> read_workspace_error(const Context& ctx, const YAML::Node& node) {
  const std::string field = "workspace_error";
  if (!node.IsMap()) return ctx.error(field, "expected a map {xyz, rpy, objects}");
  YAML::Node common(YAML::NodeType::Map);
  for (const auto& entry : node) {
    const std::string key = entry.first.Scalar();
    if (key != "xyz" && key != "rpy" && key != "objects") {
      return ctx.error(field + "." + key, "unknown key (expected xyz, rpy, objects)");
    }
    if (key != "objects") common[key] = entry.second;
  }
  if (!common["xyz"]) common["xyz"] = std::vector<double>{0.0, 0.0, 0.0};
  const auto fail = [&ctx](const Error& e) {
    return Error{"rig file '" + ctx.source + "': " + e.message};
  };
  WorkspaceError error;
  auto pose = core::yaml_pose(common, field);
  if (!pose) return fail(pose.error());
  error.common = *pose;
  if (const YAML::Node objects = node["objects"]) {
    if (!objects.IsMap()) return ctx.error(field + ".objects", "expected a map NAME: {xyz, rpy}");
    for (const auto& entry : objects) {
      const std::string name = entry.first.Scalar();
      auto object = core::yaml_pose(entry.second, field + ".objects." + name);
      if (!object) return fail(object.error());
      error.objects.emplace_back(name, *object);
    }
  }
  return error;
}

}  // namespace

bool WorkspaceError::is_identity() const {
  const auto identity = [](const Eigen::Isometry3d& T) {
    return T.matrix() == Eigen::Matrix4d::Identity();
  };
  return identity(common) && std::all_of(objects.begin(), objects.end(),
                                         [&](const auto& o) { return identity(o.second); });
}

Result<core::Workspace> apply_workspace_error(const core::Workspace& file,
                                              const WorkspaceError& error) {
  core::Workspace real = file;
  for (core::WorkspaceObject& object : real.objects) {
    object.T_base_object = error.common * object.T_base_object;
  }
  for (const auto& [name, T_error] : error.objects) {
    auto it = std::find_if(real.objects.begin(), real.objects.end(),
                           [&](const core::WorkspaceObject& o) { return o.name == name; });
    if (it == real.objects.end()) {
      return Error{"workspace_error.objects: '" + name + "' is not an object of " +
                   (file.source.empty() ? "the workspace" : file.source)};
    }
    it->T_base_object = T_error * it->T_base_object;
  }
  return real;
}

Eigen::Isometry3d StereoRig::look_at(const Eigen::Vector3d& centre_base,
                                     const Eigen::Vector3d& target_base,
                                     const Eigen::Vector3d& up_base) {
  const Eigen::Vector3d z = (target_base - centre_base).normalized();
  const Eigen::Vector3d x = z.cross(up_base).normalized();
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear().col(0) = x;
  T.linear().col(1) = y;
  T.linear().col(2) = z;
  T.translation() = centre_base;
  return T;
}

void StereoRig::update_camera_poses() {
  const Eigen::Isometry3d T_base_left =
      T_base_rig * Eigen::Translation3d(-0.5 * baseline_m, 0.0, 0.0);
  const Eigen::Isometry3d T_base_right =
      T_base_rig * Eigen::Translation3d(0.5 * baseline_m, 0.0, 0.0);
  cameras.left.T_cam_base = T_base_left.inverse();
  cameras.right.T_cam_base = T_base_right.inverse();
}

Result<StereoRig> parse_stereo_rig_yaml(const std::string& text, const std::string& source,
                                        const std::string& base_directory) {
  const Context ctx{source};
  const auto loaded = core::load_yaml(text, "rig file '" + source + "': ");
  if (!loaded) return loaded.error();
  const YAML::Node& root = *loaded;
  if (!root.IsMap()) return ctx.error("top level", "expected a map");
  for (const auto& entry : root) {
    const auto key = entry.first.as<std::string>();
    if (key != "name" && key != "robot" && key != "body" && key != "workspace" &&
        key != "workspace_error" && key != "marker" && key != "target" && key != "baseline_m" &&
        key != "pose" && key != "cameras") {
      return ctx.error(key,
                       "unknown key (expected name, robot, body, workspace, workspace_error, "
                       "marker, target, baseline_m, pose, cameras)");
    }
  }
  const auto resolve = [&](const std::string& path) {
    const fs::path p(path);
    return p.is_absolute() || base_directory.empty() ? p.string()
                                                     : (fs::path(base_directory) / p).string();
  };
  StereoRig rig;
  try {
    rig.name = root["name"] ? root["name"].as<std::string>() : fs::path(source).stem().string();
    if (!root["robot"]) return ctx.error("robot", "missing (a robot name or file)");
    rig.robot = root["robot"].as<std::string>();
    // A robot given as a file is relative to the rig file; a bare name goes to load_robot.
    if (rig.robot.find('.') != std::string::npos || rig.robot.find('/') != std::string::npos) {
      rig.robot = resolve(rig.robot);
    }
    if (root["body"]) rig.body_file = resolve(root["body"].as<std::string>());
    if (root["workspace"]) rig.workspace_file = resolve(root["workspace"].as<std::string>());
    if (root["marker"]) rig.marker_file = resolve(root["marker"].as<std::string>());
  } catch (const YAML::Exception&) {
    return ctx.error("name/robot/body/workspace/marker", "must be strings");
  }
  if (!rig.workspace_file.empty()) {
    auto workspace = core::load_workspace_file(rig.workspace_file);
    if (!workspace) return ctx.error("workspace", workspace.error().message);
    rig.workspace = std::move(*workspace);
  }
  if (const YAML::Node node = root["workspace_error"]) {
    if (rig.workspace_file.empty()) {
      return ctx.error("workspace_error", "needs a workspace: (the file it is an error of)");
    }
    auto error = read_workspace_error(ctx, node);
    if (!error) return error.error();
    auto real = apply_workspace_error(rig.workspace, *error);
    if (!real) return Error{"rig file '" + source + "': " + real.error().message};
    rig.workspace_error = std::move(*error);
    rig.workspace = std::move(*real);
  }
  if (!rig.marker_file.empty()) {
    auto marker = core::load_marker_mount_file(rig.marker_file);
    if (!marker) return ctx.error("marker", marker.error().message);
    rig.marker = *marker;
  }
  if (const YAML::Node node = root["target"]) {
    try {
      rig.target = node.as<std::string>();
    } catch (const YAML::Exception&) {
      return ctx.error("target", "must be a target spec string");
    }
    if (auto target = vision::parse_registration_target(rig.target); !target) {
      return ctx.error("target", target.error().message);
    }
  }
  if (root["baseline_m"]) {
    try {
      rig.baseline_m = root["baseline_m"].as<double>();
    } catch (const YAML::Exception&) {
      return ctx.error("baseline_m", "must be a number");
    }
    if (!(rig.baseline_m > 0.0 && rig.baseline_m < 10.0)) {
      return ctx.error("baseline_m", "must be in (0, 10) metres");
    }
  }
  const YAML::Node pose = root["pose"];
  if (!pose || !pose.IsMap()) return ctx.error("pose", "missing (centre_m, look_at_m, up)");
  auto centre = read_vector3(ctx, pose["centre_m"], "pose.centre_m");
  if (!centre) return centre.error();
  auto target = read_vector3(ctx, pose["look_at_m"], "pose.look_at_m");
  if (!target) return target.error();
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  if (pose["up"]) {
    auto value = read_vector3(ctx, pose["up"], "pose.up");
    if (!value) return value.error();
    up = *value;
  }
  const Eigen::Vector3d view = *target - *centre;
  if (view.norm() < 1e-6) return ctx.error("pose.look_at_m", "equals centre_m");
  if (up.norm() < 1e-9 || view.normalized().cross(up.normalized()).norm() < 1e-6) {
    return ctx.error("pose.up", "is zero or parallel to the viewing direction");
  }
  rig.T_base_rig = StereoRig::look_at(*centre, *target, up);

  const YAML::Node cameras = root["cameras"];
  if (!cameras || !cameras.IsMap()) return ctx.error("cameras", "missing (left: and right:)");
  auto left = read_camera(ctx, cameras["left"], "cameras.left");
  if (!left) return left.error();
  auto right = read_camera(ctx, cameras["right"], "cameras.right");
  if (!right) return right.error();
  rig.cameras.left = *left;
  rig.cameras.right = *right;
  rig.update_camera_poses();
  return rig;
}

Result<StereoRig> load_stereo_rig(const std::string& path) {
  std::ifstream in(path);
  if (!in) return Error{"rig file '" + path + "': cannot be opened (does it exist?)"};
  std::stringstream text;
  text << in.rdbuf();
  return parse_stereo_rig_yaml(text.str(), path, fs::path(path).parent_path().string());
}

std::string default_rig_file(const std::string& robot_name) {
  return (fs::path(core::data_directory()) / "rigs" / (robot_name + "_rig.yaml")).string();
}

}  // namespace telear::sim
