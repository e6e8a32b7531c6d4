#include "telear/core/workspace.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <set>

#include "telear/core/number_format.hpp"
#include "telear/core/resource_uri.hpp"
#include "telear/core/robot_loader.hpp"
#include "telear/core/yaml_reader.hpp"

namespace telear::core {
namespace {

double positive_length(const YAML::Node& node, const std::string& what) {
  if (!node) throw YamlFieldError{what + ": missing"};
  const double value = number_or_throw(node, what);
  if (!(value > 0.0)) throw YamlFieldError{what + " must be positive, got " + format_number(value)};
  return value;
}

// Where a mesh object's `file` is looked for: relative to the workspace file, package://
// through the caller's package paths, then ROS_PACKAGE_PATH.
struct MeshSearch {
  ResourceSearchPaths paths;
};

WorkspaceObject parse_object(const YAML::Node& node, const std::string& what,
                             const MeshSearch& search) {
  if (!node.IsMap()) throw YamlFieldError{what + " must be a map"};
  WorkspaceObject object;
  if (!node["name"] || !node["name"].IsScalar() || node["name"].Scalar().empty()) {
    throw YamlFieldError{what + ".name: missing (every object has a name)"};
  }
  object.name = node["name"].Scalar();
  const std::string where = "object '" + object.name + "'";
  if (!node["shape"] || !node["shape"].IsScalar()) {
    throw YamlFieldError{where + ": shape: missing (box, cylinder, sphere or mesh)"};
  }
  const std::string shape = node["shape"].Scalar();
  const std::set<std::string> common = {"name", "shape", "pose", "colour", "graspable"};
  auto keys = [&](std::initializer_list<std::string> extra) {
    std::set<std::string> allowed = common;
    allowed.insert(extra.begin(), extra.end());
    ok_or_throw(check_yaml_keys(node, allowed, where));
  };
  if (shape == "box") {
    object.shape = ShapeKind::kBox;
    keys({"size"});
    if (!node["size"]) throw YamlFieldError{where + ": size: missing ([x, y, z] in m)"};
    object.size_m = value_or_throw(yaml_vector3(node["size"], where + ": size"));
    for (int i = 0; i < 3; ++i) {
      if (!(object.size_m[i] > 0.0)) {
        throw YamlFieldError{where + ": size[" + std::to_string(i) + "] must be positive, got " +
                             format_number(object.size_m[i])};
      }
    }
  } else if (shape == "cylinder") {
    object.shape = ShapeKind::kCylinder;
    keys({"radius", "length"});
    object.radius_m = positive_length(node["radius"], where + ": radius");
    object.length_m = positive_length(node["length"], where + ": length");
  } else if (shape == "sphere") {
    object.shape = ShapeKind::kSphere;
    keys({"radius"});
    object.radius_m = positive_length(node["radius"], where + ": radius");
  } else if (shape == "mesh") {
    object.shape = ShapeKind::kMesh;
    keys({"file", "scale"});
    if (!node["file"] || !node["file"].IsScalar() || node["file"].Scalar().empty()) {
      throw YamlFieldError{where +
                           ": file: missing (the mesh file: a path relative to the "
                           "workspace file, package://PKG/PATH or file:///PATH)"};
    }
    object.mesh_file = node["file"].Scalar();
    auto resolved = resolve_resource_uri(object.mesh_file, search.paths, "mesh");
    if (!resolved) throw YamlFieldError{where + ": file: " + resolved.error().message};
    object.mesh_path = *resolved;
    if (node["scale"]) {
      object.mesh_scale = value_or_throw(yaml_vector3(node["scale"], where + ": scale"));
      for (int i = 0; i < 3; ++i) {
        if (!(object.mesh_scale[i] > 0.0)) {
          throw YamlFieldError{where + ": scale[" + std::to_string(i) + "] must be positive, got " +
                               format_number(object.mesh_scale[i])};
        }
      }
    }
  } else {
    throw YamlFieldError{where + ": unknown shape '" + shape + "' (box, cylinder, sphere or mesh)"};
  }
  if (node["pose"])
    object.T_base_object = value_or_throw(yaml_pose(node["pose"], where + ": pose"));
  if (node["colour"]) {
    const Eigen::Vector3d c = value_or_throw(yaml_vector3(node["colour"], where + ": colour"));
    if ((c.array() < 0.0).any() || (c.array() > 1.0).any()) {
      throw YamlFieldError{where + ": colour components must lie in 0..1"};
    }
    object.colour = c.cast<float>();
  }
  if (node["graspable"]) {
    try {
      object.graspable = node["graspable"].as<bool>();
    } catch (const YAML::Exception&) {
      throw YamlFieldError{where + ": graspable must be true or false, got '" +
                           node["graspable"].Scalar() + "'"};
    }
  }
  return object;
}

Result<Workspace> parse_workspace(const YAML::Node& root, const std::string& source,
                                  const std::vector<std::string>& package_paths) {
  MeshSearch search;
  search.paths.package_paths = package_paths;
  search.paths.ros_package_path = ros_package_path_from_environment();
  search.paths.base_dir =
      std::filesystem::absolute(std::filesystem::path(source)).parent_path().string();
  return catch_yaml_errors<Workspace>(source + ": ", [&]() -> Result<Workspace> {
    Workspace workspace;
    workspace.source = source;
    if (!root.IsMap()) return Error{source + ": not a workspace file (expected name, objects)"};
    ok_or_throw(check_yaml_keys(root, {"name", "objects"}, ""));
    if (root["name"]) workspace.name = root["name"].Scalar();
    const YAML::Node objects = root["objects"];
    if (!objects || !objects.IsSequence()) {
      return Error{source + ": objects: missing (a list of objects)"};
    }
    std::set<std::string> names;
    for (std::size_t i = 0; i < objects.size(); ++i) {
      WorkspaceObject object =
          parse_object(objects[i], "objects[" + std::to_string(i) + "]", search);
      if (!names.insert(object.name).second) {
        return Error{source + ": object '" + object.name + "' is named twice"};
      }
      workspace.objects.push_back(std::move(object));
    }
    return workspace;
  });
}

void append_object_sphere(Mesh& mesh, double radius, int segments, const Eigen::Vector3f& colour) {
  const int rings = std::max(2, segments / 2);
  const std::uint32_t first = static_cast<std::uint32_t>(mesh.vertices.size());
  for (int i = 0; i <= rings; ++i) {
    const double theta = std::numbers::pi * i / rings;  // from the +z pole
    for (int j = 0; j <= segments; ++j) {
      const double phi = 2.0 * std::numbers::pi * j / segments;
      const Eigen::Vector3f n(static_cast<float>(std::sin(theta) * std::cos(phi)),
                              static_cast<float>(std::sin(theta) * std::sin(phi)),
                              static_cast<float>(std::cos(theta)));
      mesh.add_vertex(n * static_cast<float>(radius), n, colour);
    }
  }
  const std::uint32_t stride = static_cast<std::uint32_t>(segments + 1);
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < segments; ++j) {
      const std::uint32_t a = first + i * stride + j, b = a + stride;
      // Counter-clockwise seen from outside.
      mesh.triangles.insert(mesh.triangles.end(), {a, b, a + 1, a + 1, b, b + 1});
    }
  }
}

}  // namespace

const char* to_string(ShapeKind kind) {
  switch (kind) {
    case ShapeKind::kBox:
      return "box";
    case ShapeKind::kCylinder:
      return "cylinder";
    case ShapeKind::kSphere:
      return "sphere";
    case ShapeKind::kMesh:
      return "mesh";
  }
  return "?";
}

Eigen::Vector3d WorkspaceObject::half_extent_base() const {
  Eigen::Vector3d half = Eigen::Vector3d::Zero();
  switch (shape) {
    case ShapeKind::kBox:
      half = size_m / 2.0;
      break;
    case ShapeKind::kCylinder:
      half = Eigen::Vector3d(radius_m, radius_m, length_m / 2.0);
      break;
    case ShapeKind::kSphere:
      half = Eigen::Vector3d::Constant(radius_m);
      break;
    case ShapeKind::kMesh: {
      // The mesh's own bounds need not be centred on its frame: the box about the frame's
      // origin that holds them is conservative.
      if (!mesh) break;
      for (const auto& v : mesh->vertices) {
        half =
            half.cwiseMax(Eigen::Vector3d(v.position[0], v.position[1], v.position[2]).cwiseAbs());
      }
      break;
    }
  }
  // The rotated box of half-extents `half` spans |R| half about the centre (a cylinder and a
  // sphere lie inside their boxes, so the bounds are conservative for them).
  return T_base_object.linear().cwiseAbs() * half;
}

Eigen::AlignedBox3d WorkspaceObject::bounds_base() const {
  const Eigen::Vector3d extent = half_extent_base();
  const Eigen::Vector3d centre = T_base_object.translation();
  return Eigen::AlignedBox3d(centre - extent, centre + extent);
}

const WorkspaceObject* Workspace::find(const std::string& name) const {
  for (const WorkspaceObject& o : objects) {
    if (o.name == name) return &o;
  }
  return nullptr;
}

const WorkspaceObject* Workspace::first_graspable() const {
  for (const WorkspaceObject& o : objects) {
    if (o.graspable) return &o;
  }
  return nullptr;
}

double Workspace::support_height(const Eigen::Vector2d& xy_base, double below_z) const {
  double height = 0.0;
  for (const WorkspaceObject& o : objects) {
    if (o.graspable) continue;
    const Eigen::AlignedBox3d b = o.bounds_base();
    if (xy_base.x() >= b.min().x() && xy_base.x() <= b.max().x() && xy_base.y() >= b.min().y() &&
        xy_base.y() <= b.max().y() && b.max().z() <= below_z) {
      height = std::max(height, b.max().z());
    }
  }
  return height;
}

Result<Workspace> parse_workspace_yaml(const std::string& text, const std::string& source,
                                       const std::vector<std::string>& package_paths) {
  auto root = load_yaml(text, source + ": ");
  if (!root) return root.error();
  return parse_workspace(*root, source, package_paths);
}

Result<Workspace> load_workspace_file(const std::string& path,
                                      const std::vector<std::string>& package_paths) {
  auto root = load_yaml_file(path, "workspace file " + path + ": ");
  if (!root) return root.error();
  return parse_workspace(*root, path, package_paths);
}

std::string default_workspace_file(const std::string& robot_name) {
  return (std::filesystem::path(data_directory()) / "workspaces" / (robot_name + "_table.yaml"))
      .string();
}

Mesh workspace_object_mesh(const WorkspaceObject& object, int segments) {
  Mesh mesh;
  switch (object.shape) {
    case ShapeKind::kBox:
      append_box(mesh, Eigen::Vector3f::Zero(), object.size_m.cast<float>(), object.colour);
      break;
    case ShapeKind::kCylinder: {
      const float h = static_cast<float>(object.length_m / 2.0);
      append_cylinder(mesh, Eigen::Vector3f(0, 0, -h), Eigen::Vector3f(0, 0, h),
                      static_cast<float>(object.radius_m), std::max(segments, kMinCylinderSegments),
                      object.colour);
      break;
    }
    case ShapeKind::kSphere:
      append_object_sphere(mesh, object.radius_m, std::max(segments, 4), object.colour);
      break;
    case ShapeKind::kMesh:
      if (object.mesh) mesh = *object.mesh;
      break;
  }
  return mesh;
}

}  // namespace telear::core
