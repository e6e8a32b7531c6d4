#pragma once
// The workspace: the named objects around the robot (a table, the box to pick), in the
// robot's base frame. One file is the single source of the scene: the simulated rig renders
// the "real" table and box from it, the operator's AR / VR views draw the same objects, and
// the simulated grasp drops a released box onto them (docs/workspace.md).
//
// File (YAML, lengths in metres, angles in radians):
//
//   name: puma560_table
//   objects:
//     - name: table_top
//       shape: box            # box | cylinder | sphere
//       size: [0.5, 0.7, 0.03]          # box: edge lengths along the object's x, y, z
//       pose: {xyz: [0.55, -0.45, 0.385], rpy: [0, 0, 0]}   # object frame in the base frame
//       colour: [0.55, 0.38, 0.22]      # RGB in 0..1 (optional, grey)
//     - name: can
//       shape: cylinder
//       radius: 0.03          # cylinder: radius and length along the object's z, centred
//       length: 0.12
//       pose: {xyz: [0.4, -0.3, 0.46]}  # rpy defaults to 0
//     - name: box
//       shape: box
//       size: [0.05, 0.05, 0.05]
//       pose: {xyz: [0.55, -0.35, 0.425]}
//       graspable: true       # can be picked by the gripper (default false)
//     - name: fixture
//       shape: mesh           # STL / COLLADA / OBJ, loaded by the geometry layer
//       file: meshes/fixture.stl    # relative to this file, or package://PKG/..., file://
//       scale: [0.001, 0.001, 0.001]  # optional, per axis (default 1)
//       pose: {xyz: [0.6, 0.2, 0.4]}
//
// Core does not read meshes (no assimp here): it resolves a mesh object's file to an existing
// absolute path (core/resource_uri.hpp: relative paths against the workspace file's
// directory, package:// through the given package paths and ROS_PACKAGE_PATH) and keeps the
// path and scale; geometry::load_workspace_meshes (geometry/workspace_meshes.hpp) loads them
// into WorkspaceObject::mesh, after which bounds and workspace_object_mesh use the mesh.
//
// Each object's frame is centred on the shape (a box's centre, a cylinder's axis midpoint, a
// sphere's centre; a mesh's frame is the mesh file's own). Unknown keys, unknown shapes,
// non-positive or non-finite sizes, duplicate names, malformed poses, bad scales and mesh files
// that cannot be found are refused with the object and the field named.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "telear/core/mesh.hpp"
#include "telear/core/result.hpp"

namespace telear::core {

enum class ShapeKind { kBox, kCylinder, kSphere, kMesh };

const char* to_string(ShapeKind kind);

struct WorkspaceObject {
  std::string name;
  ShapeKind shape = ShapeKind::kBox;
  Eigen::Vector3d size_m = Eigen::Vector3d::Zero();  // box: edges along x, y, z
  double radius_m = 0.0;                             // cylinder, sphere
  double length_m = 0.0;                             // cylinder, along z
  std::string mesh_file;  // mesh: as written in the file (package://, relative, absolute)
  std::string mesh_path;  // mesh: the existing file it resolved to (absolute)
  Eigen::Vector3d mesh_scale = Eigen::Vector3d::Ones();  // mesh: per axis, non-zero
  // mesh: the loaded surface in the object's frame (scale applied), set by the geometry
  // layer; null until then.
  std::shared_ptr<const Mesh> mesh;
  Eigen::Isometry3d T_base_object = Eigen::Isometry3d::Identity();
  Eigen::Vector3f colour{0.6f, 0.6f, 0.6f};
  bool graspable = false;

  // Half the extent of the shape's axis-aligned bounds in the base frame, along x, y, z (a
  // mesh not loaded yet: zero).
  Eigen::Vector3d half_extent_base() const;
  // The axis-aligned bounds of the shape in the base frame (min, max corners).
  Eigen::AlignedBox3d bounds_base() const;
};

struct Workspace {
  std::string name;
  std::string source;  // the file it was read from, empty for text
  std::vector<WorkspaceObject> objects;

  // The object of that name, or nullptr.
  const WorkspaceObject* find(const std::string& name) const;
  // The first object marked graspable, or nullptr.
  const WorkspaceObject* first_graspable() const;
  // Height (base z) of the highest upper face at or below `below_z` under the point (x, y)
  // among the objects that are not graspable (their axis-aligned bounds), or 0 (the floor)
  // when none is. Where a released object comes to rest.
  double support_height(const Eigen::Vector2d& xy_base, double below_z) const;
};

// `source` names the text in messages (a file name); mesh files are resolved against its
// directory. `package_paths` are searched first for package:// mesh files, then
// ROS_PACKAGE_PATH.
Result<Workspace> parse_workspace_yaml(const std::string& text, const std::string& source,
                                       const std::vector<std::string>& package_paths = {});
Result<Workspace> load_workspace_file(const std::string& path,
                                      const std::vector<std::string>& package_paths = {});

// The shipped workspace that goes with a robot name: <data>/workspaces/<robot>_table.yaml.
std::string default_workspace_file(const std::string& robot_name);

// The object's surface as a mesh in the object's frame (its colour on every vertex).
// `segments` facets round a cylinder or a sphere; a mesh object gives its loaded mesh (empty
// when not loaded).
Mesh workspace_object_mesh(const WorkspaceObject& object, int segments = 32);

}  // namespace telear::core
