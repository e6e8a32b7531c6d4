#pragma once
// Convex hulls of collision meshes: the fast collision geometry of mesh links.
//
// A distance query between two triangle meshes walks two bounding-volume trees (~100 us for
// the shipped arms' 300-400 triangle links); between two convex polytopes GJK needs a few
// support-point searches (a few us). MoveIt and Bullet therefore check hulls. One hull per link
// would fill the concave corners of an L-shaped link, so a mesh is split into its connected
// parts first (the shipped arms' links are unions of closed housings, tubes and boxes, each
// convex or nearly so) and each part becomes its hull.
//
// A hull contains its part, so the parts' hulls contain the link: a distance between hulls is
// at most the distance between the meshes (conservative: it never reports clearance that is
// not there), and can only add contacts (where a hull fills a part's concavity). The points
// are kept to within `tolerance` (relative to the part's size, default 1e-9): a point at most
// that far outside a face is taken as on it.
//
// convex_hull is an incremental hull (the quickhull family's horizon step, points in input
// order), O(n h) for n points and h hull faces: meant for a few hundred points, once at load.

#include <Eigen/Core>
#include <array>
#include <vector>

#include "telear/core/mesh.hpp"
#include "telear/core/result.hpp"
#include "telear/geometry/robot_collision.hpp"

namespace telear::geometry {

struct ConvexHull {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise seen from outside
};

// Errors: fewer than 4 points not all in one plane (within the tolerance).
Result<ConvexHull> convex_hull(const std::vector<Eigen::Vector3d>& points, double tolerance = 1e-9);

// The mesh's triangles grouped into connected parts (triangles sharing a vertex position),
// each part's vertex positions (each once). Lines are ignored.
std::vector<std::vector<Eigen::Vector3d>> connected_parts(const core::Mesh& mesh);

// A mesh shape as the hulls of its connected parts (each a kMesh shape with convex = true, in
// the same shape frame); other shapes as they are. Errors: a part that is flat (no volume).
Result<std::vector<CollisionShape>> convex_parts(const CollisionShape& shape);

// Every mesh shape of the robot's bodies replaced by convex_parts. The bodies' radii and
// motion bounds stay (a hull's vertices are some of the mesh's). Errors name the body.
Status use_convex_parts(RobotCollisionModel& robot);

// Every body of several shapes becomes one body per shape, each of the body's name, frame and
// gripper motion, with its own motion bound (update_motion_bounds): a part near a joint moves
// little about it, so continuous checking steps a close pair by that part's lever, not the
// whole link's. Parts of one body are never checked against each other (CollisionChecker
// pairs bodies of different names only), and contacts are reported per link pair.
void split_into_parts(RobotCollisionModel& robot);

}  // namespace telear::geometry
