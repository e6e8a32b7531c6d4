#include "telear/render/scene_objects.hpp"

namespace telear::render {

SceneObject make_cube(float edge_m, const Eigen::Vector3f& centre_base,
                      const Eigen::Vector3f& colour) {
  SceneObject o;
  o.name = "cube";
  core::append_box(o.mesh, Eigen::Vector3f::Zero(), Eigen::Vector3f::Constant(edge_m), colour);
  o.T_base_object.translation() = centre_base;
  return o;
}

SceneObject make_floor(float size_m, int tiles, float z_base) {
  SceneObject o;
  o.name = "floor";
  core::append_checker_floor(o.mesh, size_m, tiles, Eigen::Vector3f(0.55f, 0.55f, 0.55f),
                             Eigen::Vector3f(0.4f, 0.4f, 0.42f));
  o.T_base_object.translation() = Eigen::Vector3f(0, 0, z_base);
  return o;
}

std::vector<SceneObject> workspace_scene_objects(const core::Workspace& workspace) {
  std::vector<SceneObject> objects;
  for (const core::WorkspaceObject& object : workspace.objects) {
    SceneObject o;
    o.name = object.name;
    o.mesh = core::workspace_object_mesh(object);
    o.T_base_object = object.T_base_object.cast<float>();
    objects.push_back(std::move(o));
  }
  return objects;
}

Result<MeshSetRenderer> create_scene_renderer(const std::vector<SceneObject>& objects) {
  std::vector<const core::Mesh*> meshes;
  std::vector<Eigen::Matrix4f> matrices;
  for (const SceneObject& o : objects) {
    meshes.push_back(&o.mesh);
    matrices.push_back(o.T_base_object.matrix());
  }
  auto r = MeshSetRenderer::create(meshes);
  if (!r) return r.error();
  r->set_matrices(matrices, core::PartRange{0, static_cast<int>(matrices.size())});
  return r;
}

}  // namespace telear::render
