#pragma once
// Mesh files (STL binary and ASCII, COLLADA .dae, Wavefront .obj) read through assimp into
// one core::Mesh in the file's own frame.
//
//   p_mesh = S * T_root_node * p_file,   S = diag(scale) (the URDF <mesh scale>),
// where T_root_node is the product of the node transforms from the scene root down to each
// node instancing the mesh (COLLADA's up_axis is NOT turned into assimp's Y-up: a URDF mesh's
// coordinates are the link frame's, as ROS tools read them). Normals go through the inverse
// transpose and are renormalised; a mirroring transform (negative determinant) reverses the
// winding so triangles stay counter-clockwise seen from outside.
//
// Normals: the file's; where it has none, assimp generates them, smooth across edges whose
// crease is below the feature angle and flat across sharper ones.
// Colour, first that applies: the URDF material rgba (options.rgba), the mesh material's
// diffuse colour (assimp's stand-in material for formats without one does not count), else
// kDefaultMeshColour. The line list is the feature edges (feature_edges.hpp).
//
// Limits, so that a hostile file cannot exhaust memory: the file's size is checked BEFORE it
// is read, the vertex and triangle counts (node instances included) after import.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>

#include "telear/core/mesh.hpp"
#include "telear/core/result.hpp"

namespace telear::geometry {

inline const Eigen::Vector3f kDefaultMeshColour{0.7f, 0.7f, 0.72f};

struct MeshLimits {
  std::uintmax_t max_file_bytes = 64ull << 20;  // 64 MiB
  std::size_t max_vertices = 2'000'000;
  std::size_t max_triangles = 2'000'000;
};

struct MeshLoadOptions {
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();  // per axis, non-zero
  std::optional<Eigen::Vector4f> rgba;              // the URDF material colour, 0..1
  MeshLimits limits;
  double feature_angle_deg = 30.0;  // wire-frame crease and normal smoothing limit

  // Names the field and the violated constraint.
  Status validate() const;
};

// The extensions read (lower case, with the dot): ".stl", ".dae", ".obj".
bool is_supported_mesh_extension(const std::string& path);

// Errors name the file and the reason: missing, too large (size and limit), unsupported
// extension, unreadable or corrupt (assimp's message), no triangles, too many vertices or
// triangles (count and limit).
Result<core::Mesh> load_mesh_file(const std::string& path, const MeshLoadOptions& options = {});

}  // namespace telear::geometry
