// The level of detail for fine visual meshes: a finely tessellated sphere loses most of its
// triangles while its surface stays within the tolerance (measured, not taken from
// meshoptimizer's estimate), a zero tolerance keeps the mesh as it is, and body_for draws a
// fine mesh file lighter than it was loaded.

#include "telear/geometry/mesh_simplification.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "telear/geometry/robot_geometry.hpp"
#include "test_util/temp_dir.hpp"

namespace telear::geometry {
namespace {

constexpr float kRadius = 0.05f;

core::Mesh fine_sphere(int segments) {
  core::Mesh mesh;
  core::append_sphere(mesh, Eigen::Vector3f::Zero(), kRadius, segments, {0.5f, 0.5f, 0.5f});
  return mesh;
}

// The point of triangle abc closest to p (Ericson, Real-Time Collision Detection, 5.1.5).
Eigen::Vector3d closest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                    const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  }
  const double denominator = 1.0 / (va + vb + vc);
  return a + ab * (vb * denominator) + ac * (vc * denominator);
}

Eigen::Vector3d vertex_position(const core::Mesh& mesh, std::uint32_t index) {
  const float* p = mesh.vertices[index].position;
  return {p[0], p[1], p[2]};
}

// The simplified surface's largest distance from the true sphere: for each kept triangle, how
// far inside the sphere its point nearest the centre lies.
double largest_deviation_from_sphere(const core::Mesh& mesh) {
  double worst = 0.0;
  for (std::size_t t = 0; t < mesh.triangles.size(); t += 3) {
    const Eigen::Vector3d nearest = closest_on_triangle(
        Eigen::Vector3d::Zero(), vertex_position(mesh, mesh.triangles[t]),
        vertex_position(mesh, mesh.triangles[t + 1]), vertex_position(mesh, mesh.triangles[t + 2]));
    worst = std::max(worst, kRadius - nearest.norm());
  }
  return worst;
}

TEST(MeshSimplification, AFineSphereKeepsItsShapeWithFarFewerTriangles) {
  const core::Mesh fine = fine_sphere(128);
  const double fine_deviation = largest_deviation_from_sphere(fine);
  const double tolerance = 0.0005;
  const SimplifiedMesh lod = simplify_mesh(fine, tolerance, 30.0);
  EXPECT_LT(lod.mesh.triangle_count() * 4, fine.triangle_count())
      << lod.mesh.triangle_count() << " of " << fine.triangle_count();
  EXPECT_GT(lod.mesh.triangle_count(), 100u);  // still a sphere, not a tetrahedron
  EXPECT_LE(lod.estimated_deviation_m, tolerance / 2);
  // Measured on the result: inside the tolerance (plus the fine mesh's own chordal error).
  EXPECT_LE(largest_deviation_from_sphere(lod.mesh), tolerance + fine_deviation);
  // Unused vertices are dropped and every index is valid.
  EXPECT_LT(lod.mesh.vertices.size(), fine.vertices.size());
  for (std::uint32_t i : lod.mesh.triangles) ASSERT_LT(i, lod.mesh.vertices.size());
  EXPECT_FALSE(lod.mesh.lines.empty());  // the wire-frame is recomputed
  for (std::uint32_t i : lod.mesh.lines) ASSERT_LT(i, lod.mesh.vertices.size());
}

TEST(MeshSimplification, ATighterToleranceKeepsMoreTriangles) {
  const core::Mesh fine = fine_sphere(128);
  const SimplifiedMesh loose = simplify_mesh(fine, 0.002, 30.0);
  const SimplifiedMesh tight = simplify_mesh(fine, 0.0002, 30.0);
  EXPECT_LT(loose.mesh.triangle_count(), tight.mesh.triangle_count());
  EXPECT_LE(largest_deviation_from_sphere(tight.mesh),
            0.0002 + largest_deviation_from_sphere(fine));
}

TEST(MeshSimplification, ZeroToleranceKeepsTheMeshAsItIs) {
  const core::Mesh fine = fine_sphere(16);
  const SimplifiedMesh same = simplify_mesh(fine, 0.0, 30.0);
  EXPECT_EQ(same.mesh.triangles, fine.triangles);
  EXPECT_EQ(same.mesh.vertices.size(), fine.vertices.size());
  EXPECT_EQ(same.estimated_deviation_m, 0.0);
}

// A Wavefront OBJ of a mesh (positions and normals), the way a lab's exported link looks.
std::string obj_of(const core::Mesh& mesh) {
  std::string text;
  char line[160];
  for (const core::MeshVertex& v : mesh.vertices) {
    std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\nvn %.9g %.9g %.9g\n", v.position[0],
                  v.position[1], v.position[2], v.normal[0], v.normal[1], v.normal[2]);
    text += line;
  }
  for (std::size_t t = 0; t < mesh.triangles.size(); t += 3) {
    const auto a = mesh.triangles[t] + 1, b = mesh.triangles[t + 1] + 1,
               c = mesh.triangles[t + 2] + 1;
    std::snprintf(line, sizeof line, "f %u//%u %u//%u %u//%u\n", a, a, b, b, c, c);
    text += line;
  }
  return text;
}

TEST(MeshSimplification, BodyForDrawsAFineMeshFileAtTheLevelOfDetail) {
  test_files::TempDir tmp;
  tmp.write("link.obj", obj_of(fine_sphere(96)));
  core::RobotModel::Description chain;
  chain.name = "one";
  core::Joint joint;
  joint.name = "j1";
  joint.limits = {-3.0, 3.0, 1.0, 1.0};
  chain.joints.push_back(joint);
  auto model = core::RobotModel::create(chain);
  ASSERT_TRUE(model) << model.error().message;
  core::RobotDescription d;
  d.name = "one";
  d.model = std::make_shared<const core::RobotModel>(std::move(*model));
  d.urdf_path = (tmp.path() / "one.urdf").string();
  core::RobotLink link;
  link.name = "ball";
  link.frame = 1;
  core::GeometryElement mesh;
  mesh.kind = core::GeometryElement::Kind::kMesh;
  mesh.mesh_uri = "link.obj";
  link.visuals.push_back(mesh);
  d.links = {link};

  GeometryOptions options;
  options.ros_package_path = std::vector<std::string>{};
  auto drawn = body_for(d, options);
  ASSERT_TRUE(drawn) << drawn.error().message;
  EXPECT_EQ(drawn->mesh_file_triangles, fine_sphere(96).triangle_count());
  EXPECT_LT(drawn->drawn_mesh_triangles * 3, drawn->mesh_file_triangles);
  EXPECT_EQ(drawn->body.link_meshes[1].triangle_count(), drawn->drawn_mesh_triangles);

  options.visual_tolerance_m = 0.0;
  auto full = body_for(d, options);
  ASSERT_TRUE(full) << full.error().message;
  EXPECT_EQ(full->drawn_mesh_triangles, full->mesh_file_triangles);

  options.visual_tolerance_m = -0.001;
  auto refused = body_for(d, options);
  ASSERT_FALSE(refused);
  EXPECT_THAT(refused.error().message,
              ::testing::HasSubstr("visual_tolerance_m must be in [0, 0.01] m"));
}

}  // namespace
}  // namespace telear::geometry
