// The Session's mesh collision geometry (SessionOptions::mesh_collision, docs/collision.md,
// "Performance"): ur6's STL links are checked as the convex hulls of their parts by default,
// their triangles with kExact. The hulls contain the links, so the ghost's clearance can only
// be smaller, and on the shipped arm by at most a couple of millimetres. Not connected: no
// servers.

#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "telear/geometry/collision_checker.hpp"
#include "telear/geometry/workspace_meshes.hpp"
#include "telear/session/session.hpp"

namespace telear::session {
namespace {

std::unique_ptr<Session> offline_ur6(std::optional<geometry::MeshCollision> mesh_collision) {
  SessionOptions options;
  options.robot.address = "127.0.0.1:1";  // never connected
  options.vision.address = "127.0.0.1:1";
  auto description = core::load_robot_description({"ur6", "", {}});
  EXPECT_TRUE(description) << description.error().message;
  options.description = std::move(*description);
  auto workspace = geometry::load_workspace(core::default_workspace_file("ur6"));
  EXPECT_TRUE(workspace) << workspace.error().message;
  options.workspace = std::move(*workspace);
  if (mesh_collision) options.mesh_collision = *mesh_collision;
  auto session = Session::create(options.description->model, options);
  EXPECT_TRUE(session) << session.error().message;
  return std::move(*session);
}

TEST(SessionMeshCollision, TheGhostsClearanceIsTheHullsByDefaultAndTheMeshesWithExact) {
  EXPECT_EQ(SessionOptions{}.mesh_collision, geometry::MeshCollision::kConvexParts);
  const auto by_default = offline_ur6(std::nullopt);
  const auto hulls = offline_ur6(geometry::MeshCollision::kConvexParts);
  const auto exact = offline_ur6(geometry::MeshCollision::kExact);
  ASSERT_TRUE(by_default->checks_collisions());
  ASSERT_TRUE(exact->checks_collisions());
  const geometry::Clearance& d = by_default->ghost_clearance().workspace;
  const geometry::Clearance& h = hulls->ghost_clearance().workspace;
  const geometry::Clearance& e = exact->ghost_clearance().workspace;
  ASSERT_TRUE(std::isfinite(e.distance_m));
  EXPECT_EQ(d.distance_m, h.distance_m);
  EXPECT_EQ(d.body, h.body);
  // The same nearest pair, no farther with the hulls, and within 2 mm of the meshes.
  EXPECT_EQ(h.body, e.body);
  EXPECT_EQ(h.other, e.other);
  EXPECT_LE(h.distance_m, e.distance_m + 1e-6);
  EXPECT_GE(h.distance_m, e.distance_m - 2e-3);
}

}  // namespace
}  // namespace telear::session
