// The workspace file (include/telear/core/workspace.hpp): the shipped table scene, each
// shape, the support height a released object drops onto, and bad files refused with the
// object and the field named.
#include "telear/core/workspace.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "test_util/mesh_test_files.hpp"

namespace telear::core {
namespace {

std::string error_of(const std::string& yaml) {
  auto workspace = parse_workspace_yaml(yaml, "ws.yaml");
  EXPECT_FALSE(workspace) << "accepted:\n" << yaml;
  return workspace ? "" : workspace.error().message;
}

TEST(WorkspaceTest, TheShippedTableSceneHasTheTableTopAndTheBoxToPick) {
  auto workspace = load_workspace_file(default_workspace_file("puma560"));
  ASSERT_TRUE(workspace) << workspace.error().message;
  EXPECT_EQ(workspace->name, "puma560_table");
  const WorkspaceObject* top = workspace->find("table_top");
  ASSERT_NE(top, nullptr);
  EXPECT_NEAR(top->bounds_base().max().z(), 0.40, 1e-12);  // the table's upper face
  const WorkspaceObject* box = workspace->first_graspable();
  ASSERT_NE(box, nullptr);
  EXPECT_EQ(box->name, "box");
  // Far out on the table, where the PUMA reaches it elbow-up (the file's comment says why).
  EXPECT_TRUE(box->T_base_object.translation().isApprox(Eigen::Vector3d(0.83, 0.05, 0.425)));
  // The box rests on the table: its lower face on the table's upper face.
  EXPECT_NEAR(box->bounds_base().min().z(), top->bounds_base().max().z(), 1e-12);
}

TEST(WorkspaceTest, EachShapeParsesWithItsPoseAndBounds) {
  auto workspace = parse_workspace_yaml(R"(
name: shapes
objects:
  - name: slab
    shape: box
    size: [0.2, 0.4, 0.1]
    pose: {xyz: [1, 2, 3], rpy: [0, 0, 1.5707963267948966]}
    colour: [0.1, 0.2, 0.3]
  - name: can
    shape: cylinder
    radius: 0.05
    length: 0.3
    pose: {xyz: [0, 0, 0.15]}
    graspable: true
  - name: ball
    shape: sphere
    radius: 0.1
)",
                                        "shapes.yaml");
  ASSERT_TRUE(workspace) << workspace.error().message;
  ASSERT_EQ(workspace->objects.size(), 3u);
  const WorkspaceObject& slab = workspace->objects[0];
  EXPECT_EQ(slab.shape, ShapeKind::kBox);
  EXPECT_TRUE(slab.colour.isApprox(Eigen::Vector3f(0.1f, 0.2f, 0.3f)));
  // Turned 90 degrees about z: its 0.4 m side now runs along x.
  const Eigen::AlignedBox3d b = slab.bounds_base();
  EXPECT_NEAR(b.sizes().x(), 0.4, 1e-12);
  EXPECT_NEAR(b.sizes().y(), 0.2, 1e-12);
  EXPECT_TRUE(b.center().isApprox(Eigen::Vector3d(1, 2, 3)));
  const WorkspaceObject& can = workspace->objects[1];
  EXPECT_EQ(can.shape, ShapeKind::kCylinder);
  EXPECT_TRUE(can.graspable);
  EXPECT_NEAR(can.bounds_base().min().z(), 0.0, 1e-12);
  EXPECT_EQ(workspace->first_graspable(), &can);
  EXPECT_EQ(workspace->objects[2].shape, ShapeKind::kSphere);
  EXPECT_FALSE(workspace->objects[2].graspable);
  EXPECT_EQ(workspace->find("nothing"), nullptr);
}

TEST(WorkspaceTest, ARelasedObjectRestsOnTheHighestFaceBelowItOrOnTheFloor) {
  auto workspace = load_workspace_file(default_workspace_file("puma560"));
  ASSERT_TRUE(workspace) << workspace.error().message;
  EXPECT_NEAR(workspace->support_height({0.55, -0.45}, 1.0), 0.40, 1e-12);  // over the table
  EXPECT_NEAR(workspace->support_height({0.0, 0.6}, 1.0), 0.0, 1e-12);      // beside it
  // Under the table top (between the legs) the floor holds it.
  EXPECT_NEAR(workspace->support_height({0.55, -0.45}, 0.2), 0.0, 1e-12);
  // The graspable box itself is no support.
  EXPECT_NEAR(workspace->support_height({0.83, 0.05}, 1.0), 0.40, 1e-12);
}

TEST(WorkspaceTest, MeshesHaveTheShapesExtentInTheObjectsFrame) {
  WorkspaceObject box;
  box.size_m = Eigen::Vector3d(0.2, 0.4, 0.6);
  WorkspaceObject cylinder;
  cylinder.shape = ShapeKind::kCylinder;
  cylinder.radius_m = 0.1;
  cylinder.length_m = 0.5;
  WorkspaceObject sphere;
  sphere.shape = ShapeKind::kSphere;
  sphere.radius_m = 0.25;
  for (const WorkspaceObject* object : {&box, &cylinder, &sphere}) {
    const Mesh mesh = workspace_object_mesh(*object, 24);
    ASSERT_FALSE(mesh.triangles.empty()) << to_string(object->shape);
    Eigen::AlignedBox3f extent;
    extent.setEmpty();
    for (const MeshVertex& v : mesh.vertices) {
      extent.extend(Eigen::Vector3f(v.position[0], v.position[1], v.position[2]));
    }
    const Eigen::AlignedBox3d expected = object->bounds_base();  // identity pose
    EXPECT_TRUE(extent.min().cast<double>().isApprox(expected.min(), 1e-6))
        << to_string(object->shape);
    EXPECT_TRUE(extent.max().cast<double>().isApprox(expected.max(), 1e-6))
        << to_string(object->shape);
  }
}

TEST(WorkspaceTest, BadFilesAreRefusedWithTheObjectAndTheFieldNamed) {
  EXPECT_EQ(error_of("objects:\n  - {name: a, shape: box, size: [1, -2, 1]}\n"),
            "ws.yaml: object 'a': size[1] must be positive, got -2");
  EXPECT_EQ(error_of("objects:\n  - {name: a, shape: box, size: [1, .nan, 1]}\n"),
            "ws.yaml: object 'a': size[1]: must be finite, got .nan");
  EXPECT_EQ(error_of("objects:\n  - {name: a, shape: cone, radius: 1}\n"),
            "ws.yaml: object 'a': unknown shape 'cone' (box, cylinder, sphere or mesh)");
  EXPECT_EQ(error_of("objects:\n  - {name: a, shape: sphere}\n"),
            "ws.yaml: object 'a': radius: missing");
  EXPECT_EQ(error_of("objects:\n  - {name: a, shape: sphere, radius: 1, size: [1, 1, 1]}\n"),
            "ws.yaml: object 'a': unknown key 'size' (expected colour, graspable, name, pose, "
            "radius, shape)");
  EXPECT_EQ(error_of("objects:\n  - {name: a, shape: sphere, radius: 1, pose: {xyz: [1, 2]}}\n"),
            "ws.yaml: object 'a': pose.xyz must be a list of 3 numbers");
  EXPECT_EQ(error_of("objects:\n  - {shape: sphere, radius: 1}\n"),
            "ws.yaml: objects[0].name: missing (every object has a name)");
  EXPECT_EQ(error_of("objects:\n  - {name: a, shape: sphere, radius: 1}\n"
                     "  - {name: a, shape: sphere, radius: 2}\n"),
            "ws.yaml: object 'a' is named twice");
  EXPECT_EQ(error_of("objects:\n  - {name: a, shape: sphere, radius: 1, graspable: maybe}\n"),
            "ws.yaml: object 'a': graspable must be true or false, got 'maybe'");
  EXPECT_EQ(error_of("objects:\n  - {name: a, shape: sphere, radius: 1, colour: [2, 0, 0]}\n"),
            "ws.yaml: object 'a': colour components must lie in 0..1");
  EXPECT_EQ(error_of("name: x\n"), "ws.yaml: objects: missing (a list of objects)");
  EXPECT_EQ(error_of("[1, 2]"), "ws.yaml: not a workspace file (expected name, objects)");
  EXPECT_NE(error_of("objects: [").find("ws.yaml: not valid YAML"), std::string::npos);
  auto missing = load_workspace_file("/nonexistent/ws.yaml");
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().message, "workspace file /nonexistent/ws.yaml: cannot be read");
}

// A mesh object keeps its file resolved to an absolute path (relative to the workspace file,
// or inside a package) and its scale; core does not read the mesh (the geometry layer does).
TEST(WorkspaceTest, AMeshObjectResolvesItsFileAgainstTheWorkspaceFileAndAPackage) {
  test_files::TempDir dir;
  const std::string stl = dir.write("scene/meshes/cube.stl", test_files::binary_stl_cube());
  dir.write("pkgs/fixtures/package.xml", "<package/>");
  const std::string packaged =
      dir.write("pkgs/fixtures/meshes/cube.stl", test_files::binary_stl_cube());
  const std::string path = dir.write("scene/ws.yaml", R"(
objects:
  - name: fixture
    shape: mesh
    file: meshes/cube.stl
    scale: [0.1, 0.2, 0.3]
    pose: {xyz: [1, 0, 0]}
  - name: packaged
    shape: mesh
    file: package://fixtures/meshes/cube.stl
)");
  auto workspace = load_workspace_file(path, {(dir.path() / "pkgs").string()});
  ASSERT_TRUE(workspace) << workspace.error().message;
  const WorkspaceObject& fixture = workspace->objects[0];
  EXPECT_EQ(fixture.shape, ShapeKind::kMesh);
  EXPECT_EQ(fixture.mesh_file, "meshes/cube.stl");
  EXPECT_EQ(std::filesystem::canonical(fixture.mesh_path), std::filesystem::canonical(stl));
  EXPECT_TRUE(fixture.mesh_scale.isApprox(Eigen::Vector3d(0.1, 0.2, 0.3)));
  EXPECT_EQ(fixture.mesh, nullptr);  // not loaded by core
  EXPECT_TRUE(fixture.half_extent_base().isZero());
  EXPECT_EQ(std::filesystem::canonical(workspace->objects[1].mesh_path),
            std::filesystem::canonical(packaged));
  EXPECT_TRUE(workspace->objects[1].mesh_scale.isApprox(Eigen::Vector3d::Ones()));
}

TEST(WorkspaceTest, BadMeshObjectsAreRefusedWithTheObjectAndTheFieldNamed) {
  test_files::TempDir dir;
  dir.write("cube.stl", test_files::binary_stl_cube());
  auto error = [&](const std::string& object) {
    const std::string path = dir.write("ws.yaml", "objects:\n  - " + object + "\n");
    auto workspace = load_workspace_file(path);
    EXPECT_FALSE(workspace) << object;
    const std::string prefix = path + ": ";
    if (workspace) return std::string();
    const std::string& message = workspace.error().message;
    EXPECT_EQ(message.rfind(prefix, 0), 0u) << message;
    return message.substr(std::min(message.size(), prefix.size()));
  };
  EXPECT_EQ(error("{name: m, shape: mesh}"),
            "object 'm': file: missing (the mesh file: a path relative to the workspace file, "
            "package://PKG/PATH or file:///PATH)");
  EXPECT_EQ(error("{name: m, shape: mesh, file: cube.stl, scale: [1, 0, 1]}"),
            "object 'm': scale[1] must be positive, got 0");
  EXPECT_EQ(error("{name: m, shape: mesh, file: cube.stl, scale: [1, .nan, 1]}"),
            "object 'm': scale[1]: must be finite, got .nan");
  EXPECT_EQ(error("{name: m, shape: mesh, file: cube.stl, radius: 1}"),
            "object 'm': unknown key 'radius' (expected colour, file, graspable, name, pose, "
            "scale, shape)");
  const std::string missing = error("{name: m, shape: mesh, file: nowhere.stl}");
  EXPECT_EQ(missing.rfind("object 'm': file: mesh 'nowhere.stl'", 0), 0u) << missing;
  const std::string package = error("{name: m, shape: mesh, file: package://nopkg/a.stl}");
  EXPECT_EQ(package.rfind("object 'm': file: mesh 'package://nopkg/a.stl' not found", 0), 0u)
      << package;
}

}  // namespace
}  // namespace telear::core
