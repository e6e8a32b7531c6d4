#include "telear/geometry/workspace_meshes.hpp"

#include <memory>

namespace telear::geometry {

Status load_workspace_meshes(core::Workspace& workspace, const MeshLimits& limits) {
  for (core::WorkspaceObject& object : workspace.objects) {
    if (object.shape != core::ShapeKind::kMesh || object.mesh) continue;
    MeshLoadOptions options;
    options.scale = object.mesh_scale;
    options.rgba = Eigen::Vector4f(object.colour.x(), object.colour.y(), object.colour.z(), 1.0f);
    options.limits = limits;
    Result<core::Mesh> mesh = load_mesh_file(object.mesh_path, options);
    if (!mesh) {
      return Error{workspace.source + ": object '" + object.name + "': " + mesh.error().message};
    }
    object.mesh = std::make_shared<const core::Mesh>(std::move(*mesh));
  }
  return Status::Ok();
}

Result<core::Workspace> load_workspace(const std::string& path,
                                       const std::vector<std::string>& package_paths,
                                       const MeshLimits& limits) {
  Result<core::Workspace> workspace = core::load_workspace_file(path, package_paths);
  if (!workspace) return workspace.error();
  if (Status s = load_workspace_meshes(*workspace, limits); !s) return s.error();
  return workspace;
}

}  // namespace telear::geometry
