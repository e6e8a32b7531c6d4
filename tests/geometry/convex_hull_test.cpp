// Convex hulls of collision meshes (geometry/convex_hull.hpp): a closed outward hull holding
// every input point, a mesh split into its connected parts, and the hull option of the checker
// conservative against the exact meshes on the shipped arm.

#include "telear/geometry/convex_hull.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>
#include <random>

#include "telear/core/random_configuration.hpp"
#include "telear/geometry/collision_checker.hpp"

namespace telear::geometry {
namespace {

// Closed: every directed edge once, its reverse once (two faces per edge, consistent
// winding); Euler V - E + F = 2; every point on or inside every face plane.
void expect_closed_hull(const ConvexHull& hull, const std::vector<Eigen::Vector3d>& points) {
  std::map<std::pair<int, int>, int> edges;
  for (const auto& t : hull.triangles) {
    for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
  }
  for (const auto& [edge, count] : edges) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(edges.count({edge.second, edge.first}), 1u);
  }
  const auto V = static_cast<long>(hull.vertices.size());
  const auto E = static_cast<long>(edges.size() / 2);
  const auto F = static_cast<long>(hull.triangles.size());
  EXPECT_EQ(V - E + F, 2);
  for (const auto& t : hull.triangles) {
    const Eigen::Vector3d& a = hull.vertices[static_cast<std::size_t>(t[0])];
    const Eigen::Vector3d n = (hull.vertices[static_cast<std::size_t>(t[1])] - a)
                                  .cross(hull.vertices[static_cast<std::size_t>(t[2])] - a)
                                  .normalized();
    for (const Eigen::Vector3d& p : points) EXPECT_LE(n.dot(p - a), 1e-9);
  }
}

TEST(ConvexHull, ACubeWithInnerAndFacePointsIsItsCorners) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 8; ++i) points.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  points.emplace_back(0.5, 0.5, 0.5);  // inside
  points.emplace_back(0.5, 0.5, 1.0);  // on a face
  points.emplace_back(0.5, 0.0, 0.0);  // on an edge
  points.emplace_back(1.0, 1.0, 1.0);  // repeated
  auto hull = convex_hull(points);
  ASSERT_TRUE(hull) << hull.error().message;
  EXPECT_EQ(hull->vertices.size(), 8u);
  EXPECT_EQ(hull->triangles.size(), 12u);
  expect_closed_hull(*hull, points);
}

TEST(ConvexHull, RandomPointsAreAllInside) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal;
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 400; ++i) {
    const Eigen::Vector3d p(normal(rng), normal(rng), normal(rng));
    points.push_back(i % 2 ? p.normalized() * 0.2 : p * 0.02);  // a sphere and a cloud inside
  }
  auto hull = convex_hull(points);
  ASSERT_TRUE(hull) << hull.error().message;
  EXPECT_EQ(hull->vertices.size(), 200u);  // every point of the sphere, none of the cloud
  expect_closed_hull(*hull, points);
}

TEST(ConvexHull, FlatOrTooFewPointsAreRefused) {
  auto few = convex_hull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 0, 0}});
  ASSERT_FALSE(few);
  EXPECT_EQ(few.error().message, "convex hull: fewer than 4 distinct points");
  auto flat = convex_hull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0.5, 0.2, 0}});
  ASSERT_FALSE(flat);
  EXPECT_EQ(flat.error().message, "convex hull: the points lie in a plane (no volume)");
}

// Two tetrahedra that share no vertex are two parts; positions repeated per triangle (as an
// STL gives them) are one vertex.
TEST(ConvexHull, AMeshSplitsIntoItsConnectedParts) {
  core::Mesh mesh;
  const Eigen::Vector3f n = Eigen::Vector3f::UnitZ();
  for (float shift : {0.0f, 2.0f}) {
    const Eigen::Vector3f c[4] = {{shift, 0, 0}, {shift + 1, 0, 0}, {shift, 1, 0}, {shift, 0, 1}};
    for (const auto& t :
         {std::array{0, 2, 1}, std::array{0, 1, 3}, std::array{0, 3, 2}, std::array{1, 2, 3}}) {
      for (int k : t) mesh.triangles.push_back(mesh.add_vertex(c[k], n, n));
    }
  }
  const auto parts = connected_parts(mesh);
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_EQ(parts[0].size(), 4u);
  EXPECT_EQ(parts[1].size(), 4u);
  EXPECT_EQ(parts[1][0].x(), 2.0);
}

// On ur6 (STL collision meshes) the convex parts are conservative: at random configurations
// every pair's hull distance is at most its mesh distance (to FCL's tolerance), and close to
// it (the shipped links are unions of convex parts).
TEST(ConvexHull, TheConvexPartsOfTheShippedArmAreConservative) {
  auto d = core::load_robot_description({"ur6", "", {}});
  ASSERT_TRUE(d) << d.error().message;
  auto exact = make_collision_checker(*d, core::Workspace{});
  ASSERT_TRUE(exact) << exact.error().message;
  CollisionSetupOptions options;
  options.mesh_collision = MeshCollision::kConvexParts;
  auto hulls = make_collision_checker(*d, core::Workspace{}, options);
  ASSERT_TRUE(hulls) << hulls.error().message;
  ASSERT_EQ(hulls->pairs().size(), exact->pairs().size());
  std::size_t parts = 0;
  for (const CollisionBody& b : hulls->robot().bodies) {
    for (const CollisionShape& s : b.shapes) parts += s.convex ? 1 : 0;
  }
  EXPECT_GT(parts, hulls->robot().bodies.size());  // links of several parts
  std::mt19937_64 rng(5);
  double worst_gap = 0.0;
  for (int i = 0; i < 30; ++i) {
    const Eigen::VectorXd q = core::random_configuration(*d->model, rng);
    exact->set_configuration(q, 0.5);
    hulls->set_configuration(q, 0.5);
    for (std::size_t p = 0; p < exact->pairs().size(); ++p) {
      const double mesh = exact->distance(exact->pairs()[p]).distance_m;
      const double hull = hulls->distance(hulls->pairs()[p]).distance_m;
      if (mesh <= 0.0) continue;  // in contact: the hulls are too
      EXPECT_LE(hull, mesh + 1e-6) << "pair " << p;
      worst_gap = std::max(worst_gap, mesh - hull);
    }
  }
  std::cout << "ur6 convex parts: largest distance lost to the hulls " << worst_gap * 1e3
            << " mm\n";
}

}  // namespace
}  // namespace telear::geometry
