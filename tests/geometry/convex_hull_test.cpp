// Convex hulls of collision meshes (geometry/convex_hull.hpp): a closed outward hull holding
// every input point, a mesh split into its connected parts, and the hull option of the checker
// conservative against the exact meshes on the shipped arm.

#include "telear/geometry/convex_hull.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>
#include <random>

#include "telear/core/random_configuration.hpp"
#include "telear/core/trajectory.hpp"
#include "telear/geometry/collision_checker.hpp"
#include "telear/geometry/trajectory_collision.hpp"
#include "telear/geometry/workspace_meshes.hpp"

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

// On the shipped mesh arms (STL collision meshes) the convex parts are conservative: at random
// configurations every pair's hull distance is at most its mesh distance (to FCL's tolerance),
// and within 2 mm of it (the shipped links are unions of convex parts; docs/collision.md
// states the figures printed here); every contact of the meshes is one of the hulls', reported
// once per link pair.
void expect_conservative_parts(const std::string& robot) {
  SCOPED_TRACE(robot);
  auto d = core::load_robot_description({robot, "", {}});
  ASSERT_TRUE(d) << d.error().message;
  CollisionSetupOptions exact_options;
  exact_options.mesh_collision = MeshCollision::kExact;
  auto exact = make_collision_checker(*d, core::Workspace{}, exact_options);
  ASSERT_TRUE(exact) << exact.error().message;
  CollisionSetupOptions options;
  options.mesh_collision = MeshCollision::kConvexParts;
  auto hulls = make_collision_checker(*d, core::Workspace{}, options);
  ASSERT_TRUE(hulls) << hulls.error().message;
  // Convex parts are the default (validation everywhere uses them); kExact is the way back.
  auto by_default = make_collision_checker(*d, core::Workspace{});
  ASSERT_TRUE(by_default) << by_default.error().message;
  EXPECT_EQ(by_default->robot().bodies.size(), hulls->robot().bodies.size());
  EXPECT_EQ(by_default->pairs().size(), hulls->pairs().size());
  // Split into parts: one body per part, of the link's name; pairs of different links only.
  EXPECT_GT(hulls->robot().bodies.size(), exact->robot().bodies.size());
  EXPECT_GT(hulls->pairs().size(), exact->pairs().size());
  for (const CollisionBody& b : hulls->robot().bodies) {
    ASSERT_EQ(b.shapes.size(), 1u) << b.name;
    EXPECT_TRUE(b.shapes[0].kind != core::GeometryElement::Kind::kMesh || b.shapes[0].convex)
        << b.name;  // primitives stay primitives
  }
  // The smallest distance of each link pair.
  const auto by_names = [](CollisionChecker& checker) {
    std::map<std::pair<std::string, std::string>, double> out;
    for (const CollisionPair& pair : checker.pairs()) {
      const auto key = std::pair{checker.robot().bodies[static_cast<std::size_t>(pair.body)].name,
                                 checker.pair_other_name(pair)};
      const double d = checker.distance(pair).distance_m;
      auto [it, added] = out.emplace(key, d);
      if (!added) it->second = std::min(it->second, d);
    }
    return out;
  };
  std::mt19937_64 rng(5);
  double worst_gap = 0.0;
  for (int i = 0; i < 30; ++i) {
    const Eigen::VectorXd q = core::random_configuration(*d->model, rng);
    exact->set_configuration(q, 0.5);
    hulls->set_configuration(q, 0.5);
    const auto mesh = by_names(*exact);
    const auto hull = by_names(*hulls);
    ASSERT_EQ(mesh.size(), hull.size());
    for (const auto& [names, distance] : mesh) {
      ASSERT_TRUE(hull.count(names)) << names.first << " / " << names.second;
      if (distance <= 0.0) continue;  // in contact: the hulls are too
      EXPECT_LE(hull.at(names), distance + 1e-6) << names.first << " / " << names.second;
      worst_gap = std::max(worst_gap, distance - hull.at(names));
    }
    // The same contacts, one per link pair.
    const CollisionReport a = exact->check(q), b = hulls->check(q);
    for (const Contact& c : a.contacts) {
      EXPECT_EQ(
          std::count_if(b.contacts.begin(), b.contacts.end(),
                        [&](const Contact& h) { return h.body == c.body && h.other == c.other; }),
          1)
          << c.body << " / " << c.other;
    }
  }
  EXPECT_LT(worst_gap, 2e-3);
  std::cout << robot << " convex parts: largest distance lost to the hulls " << worst_gap * 1e3
            << " mm\n";
}

TEST(ConvexHull, TheConvexPartsOfTheShippedArmsAreConservative) {
  expect_conservative_parts("ur6");
  expect_conservative_parts("arm7");
}

// Along a plan into the tray, the hulls find the contact the meshes find, no later (they
// contain the links), once per link pair although several parts touch.
TEST(ConvexHull, APlanIntoTheTrayCollidesWithTheHullsNoLater) {
  auto d = core::load_robot_description({"ur6", "", {}});
  ASSERT_TRUE(d) << d.error().message;
  auto workspace = load_workspace(core::default_workspace_file("ur6"));
  ASSERT_TRUE(workspace) << workspace.error().message;
  CollisionSetupOptions exact_options;
  exact_options.mesh_collision = MeshCollision::kExact;
  auto exact = make_collision_checker(*d, *workspace, exact_options);
  ASSERT_TRUE(exact) << exact.error().message;
  CollisionSetupOptions options;
  options.mesh_collision = MeshCollision::kConvexParts;
  auto hulls = make_collision_checker(*d, *workspace, options);
  ASSERT_TRUE(hulls) << hulls.error().message;
  // The first seeded configuration whose wrist is in the tray.
  const Eigen::VectorXd home = *d->model->named_configuration("home");
  std::mt19937_64 rng(11);
  Eigen::VectorXd into;
  for (int i = 0; i < 5000 && into.size() == 0; ++i) {
    const Eigen::VectorXd q = core::random_configuration(*d->model, rng);
    for (const Contact& c : exact->check(q).contacts) {
      if (c.other == "tray" && c.body != "base_link") into = q;
    }
  }
  ASSERT_GT(into.size(), 0);
  auto plan = core::Trajectory::create(*d->model, {{home}, {into}});
  ASSERT_TRUE(plan) << plan.error().message;
  auto by_mesh = check_trajectory(*exact, *plan);
  auto by_hull = check_trajectory(*hulls, *plan);
  ASSERT_TRUE(by_mesh) << by_mesh.error().message;
  ASSERT_TRUE(by_hull) << by_hull.error().message;
  const auto first_with_tray = [](const TrajectoryCheckReport& r) {
    for (const PlanCollision& c : r.collisions) {
      if (c.other == "tray") return c.time_s;
    }
    return -1.0;
  };
  const double mesh_t = first_with_tray(*by_mesh), hull_t = first_with_tray(*by_hull);
  ASSERT_GE(mesh_t, 0.0);
  ASSERT_GE(hull_t, 0.0);
  EXPECT_LE(hull_t, mesh_t + 1e-3);
  std::map<std::pair<std::string, double>, int> episodes;
  for (const PlanCollision& c : by_hull->collisions) {
    const int seen = ++episodes[std::pair{c.body + "/" + c.other, c.time_s}];
    EXPECT_EQ(seen, 1) << c.body << " / " << c.other;
  }
}

}  // namespace
}  // namespace telear::geometry
