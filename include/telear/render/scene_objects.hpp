#pragma once
// Objects of the scene around the arm: the seed's benchmark cube, a floor plane and the
// workspace's objects. They are
// parts of a MeshSetRenderer like the arm's links, placed once with T_base_object.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "telear/core/mesh.hpp"
#include "telear/core/result.hpp"
#include "telear/core/workspace.hpp"
#include "telear/render/mesh_set_renderer.hpp"

namespace telear::render {

struct SceneObject {
  std::string name;
  core::Mesh mesh;  // in the object's frame
  Eigen::Isometry3f T_base_object = Eigen::Isometry3f::Identity();
};

// A cube of edge `edge_m` whose centre is at `centre_base`.
SceneObject make_cube(float edge_m, const Eigen::Vector3f& centre_base,
                      const Eigen::Vector3f& colour = Eigen::Vector3f(0.8f, 0.25f, 0.2f));

// A checkered square floor of edge `size_m`, tiles x tiles, at height z_base (normal +z).
SceneObject make_floor(float size_m, int tiles, float z_base = 0.0f);

// The workspace's objects (include/telear/core/workspace.hpp) at their poses, each with its
// colour: the operator's copy of the scene for the VR view and the AR view's objects.
std::vector<SceneObject> workspace_scene_objects(const core::Workspace& workspace);

// Uploads the objects and sets their matrices. Needs a current context.
Result<MeshSetRenderer> create_scene_renderer(const std::vector<SceneObject>& objects);

}  // namespace telear::render
