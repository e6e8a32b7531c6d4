#pragma once
// Loads the mesh objects of a workspace (core/workspace.hpp: `shape: mesh`). Core parses the
// file and resolves each mesh file to a path but reads no mesh (it has no assimp); this is
// where the meshes are read (mesh_file.hpp), with the object's scale and colour, into
// WorkspaceObject::mesh, in the object's frame. After it, the object's bounds, its drawn mesh
// (core::workspace_object_mesh) and its collision shape use the mesh.

#include <string>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/core/workspace.hpp"
#include "telear/geometry/mesh_file.hpp"

namespace telear::geometry {

// Errors name the workspace file, the object and the mesh loader's reason (missing, corrupt,
// too large, no triangles).
Status load_workspace_meshes(core::Workspace& workspace, const MeshLimits& limits = {});

// core::load_workspace_file, then load_workspace_meshes.
Result<core::Workspace> load_workspace(const std::string& path,
                                       const std::vector<std::string>& package_paths = {},
                                       const MeshLimits& limits = {});

}  // namespace telear::geometry
