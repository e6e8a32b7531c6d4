// The robot server's collision guard checks mesh links as the convex hulls of their parts by
// default and their triangles with kExact (RobotServerOptions::mesh_collision, `telear
// robot-server --exact-meshes`; docs/collision.md, "Performance"): either way a jog into a
// contact is refused naming the same link and other, and a free jog goes through.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>

#include "telear/core/random_configuration.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/geometry/carried_objects.hpp"
#include "telear/geometry/collision_checker.hpp"
#include "telear/geometry/workspace_meshes.hpp"
#include "telear/net/motion_collision_guard.hpp"
#include "telear/net/robot_server.hpp"

namespace telear::net {
namespace {

using ::testing::HasSubstr;

// ur6's checker in the shipped scene (graspable objects left out, as the guard does).
geometry::CollisionChecker checker(const core::RobotDescription& d, const core::Workspace& w,
                                   geometry::MeshCollision mesh) {
  geometry::CollisionSetupOptions setup;
  setup.mesh_collision = mesh;
  auto made = geometry::make_collision_checker(d, geometry::static_obstacles(w), setup);
  EXPECT_TRUE(made) << made.error().message;
  return std::move(*made);
}

bool free(geometry::CollisionChecker& c, const Eigen::VectorXd& q) {
  return c.check(q, 0.0).collision_free();
}

TEST(RobotMeshCollision, TheGuardUsesTheHullsByDefaultAndTheMeshesWhenAsked) {
  EXPECT_EQ(RobotServerOptions{}.mesh_collision, geometry::MeshCollision::kConvexParts);
  auto d = core::load_robot_description({"ur6", "", {}});
  ASSERT_TRUE(d) << d.error().message;
  auto w = geometry::load_workspace(core::default_workspace_file("ur6"));
  ASSERT_TRUE(w) << w.error().message;
  geometry::CollisionChecker meshes = checker(*d, *w, geometry::MeshCollision::kExact);
  // From `ready` toward the first seeded configuration in contact, 5 mrad past the first point
  // the meshes find in contact (bisection).
  const Eigen::VectorXd from = *d->model->named_configuration("ready");
  const Eigen::VectorXd home = *d->model->named_configuration("home");
  ASSERT_TRUE(free(meshes, from));
  std::mt19937_64 rng(3);
  Eigen::VectorXd bad = core::random_configuration(*d->model, rng);
  while (free(meshes, bad)) bad = core::random_configuration(*d->model, rng);
  double lo = 0.0, hi = 1.0;
  for (int k = 0; k < 40; ++k) {
    const double mid = 0.5 * (lo + hi);
    (free(meshes, from + mid * (bad - from)) ? lo : hi) = mid;
  }
  const double past = std::min(1.0, hi + 0.005 / (bad - from).cwiseAbs().maxCoeff());
  const Eigen::VectorXd into = from + past * (bad - from);
  // Both guards: the same contact refused, naming the same link, and a free jog accepted.
  std::string messages[2];
  int i = 0;
  for (const geometry::MeshCollision mesh :
       {geometry::MeshCollision::kConvexParts, geometry::MeshCollision::kExact}) {
    auto guard = MotionCollisionGuard::create(*d, *w, "", kDefaultSafetyMarginM, mesh);
    ASSERT_TRUE(guard) << guard.error().message;
    const Status ok = (*guard)->check_jog(*d->model, from, home, 0.0);
    EXPECT_TRUE(ok) << ok.error().message;
    const Status refused = (*guard)->check_jog(*d->model, from, into, 0.0);
    ASSERT_FALSE(refused);
    EXPECT_THAT(refused.error().message, HasSubstr("jog collides: "));
    messages[i++] = refused.error().message.substr(0, refused.error().message.find(" (depth"));
  }
  EXPECT_EQ(messages[0], messages[1]);
}

}  // namespace
}  // namespace telear::net
