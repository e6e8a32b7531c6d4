#pragma once
// Collision checking and clearance of a robot against its workspace and itself (FCL).
//
// At one configuration q (and gripper fraction f), check(q, f) poses every robot body
// (robot_collision.hpp) and answers
//   - contacts: every pair in contact, robot body against workspace object or against another
//     robot body not allowed to touch it (allowed_collisions.hpp), with the penetration depth
//     FCL reports (the deepest contact point of the pair; 0 where FCL gives no depth, e.g.
//     between two meshes);
//   - the minimum clearance: the smallest distance between a body and an object or another
//     body over the pairs not in contact, with the two witness points in the base frame.
// Pairs: every body with every workspace object; every body pair the matrix does not allow.
// Pairs whose axis-aligned bounds are farther apart than the best distance found so far are
// skipped (their distance cannot be smaller), as are, for contacts, pairs whose bounds are
// disjoint.
//
// An object held in the gripper (attach) is a body on the tip: it moves with the arm, is
// checked against the workspace and the arm, and may touch the bodies on the tip's frame
// (the hand and fingers holding it). A workspace object of the same name is no longer an
// obstacle while it is held.
//
// Distances are exact for pairs of spheres, boxes, cylinders and convex hulls to FCL's
// tolerance (1e-6 m): sphere-box and sphere-cylinder analytically, the others by GJK; meshes
// through an OBBRSS bounding-volume tree. Within a pair of bodies, shape pairs whose bounds are
// farther apart than the nearest shape pair found so far are skipped. The checker caches poses and
// FCL objects: one per thread.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/core/workspace.hpp"
#include "telear/geometry/allowed_collisions.hpp"
#include "telear/geometry/robot_collision.hpp"

namespace telear::geometry {

struct Contact {
  std::string body;      // the robot body
  std::string other;     // the workspace object or the other robot body
  bool self = false;     // `other` is a robot body
  double depth_m = 0.0;  // penetration depth, >= 0
  Eigen::Vector3d point_base = Eigen::Vector3d::Zero();  // a contact point
};

struct Clearance {
  double distance_m = std::numeric_limits<double>::infinity();  // inf: nothing to check
  std::string body, other;
  bool self = false;
  Eigen::Vector3d p_body_base = Eigen::Vector3d::Zero();   // witness point on the body
  Eigen::Vector3d p_other_base = Eigen::Vector3d::Zero();  // witness point on the other
};

struct CollisionReport {
  std::vector<Contact> contacts;
  Clearance min_clearance;  // over the pairs not in contact
  bool collision_free() const { return contacts.empty(); }
};

// One checked pair (for continuous checking): indices into the robot's bodies, and into the
// workspace objects (other_object >= 0) or the bodies (other_body >= 0).
struct CollisionPair {
  int body = -1;
  int other_body = -1;
  int other_object = -1;
};

struct PairDistance {
  double distance_m = 0.0;     // <= 0: in contact
  double lower_bound_m = 0.0;  // the true distance is at least this (see distance())
  Eigen::Vector3d p_body_base = Eigen::Vector3d::Zero(), p_other_base = Eigen::Vector3d::Zero();
};

class CollisionChecker {
 public:
  // `workspace`'s mesh objects must be loaded (workspace_meshes.hpp); a mesh object that is
  // not is an error naming it.
  static Result<CollisionChecker> create(RobotCollisionModel robot,
                                         const core::Workspace& workspace,
                                         AllowedCollisionMatrix allowed);
  CollisionChecker(CollisionChecker&&) noexcept;
  CollisionChecker& operator=(CollisionChecker&&) noexcept;
  ~CollisionChecker();

  const RobotCollisionModel& robot() const;
  const AllowedCollisionMatrix& allowed() const;
  const std::vector<std::string>& object_names() const;
  const std::vector<CollisionPair>& pairs() const;  // the pairs checked
  std::string pair_other_name(const CollisionPair& pair) const;

  // Holds `shapes` (in the object's frame) at T_tool_object in the tip's tool frame; a
  // workspace object named `name` stops being an obstacle. Errors: a body of that name exists.
  Status attach(const std::string& name, std::vector<CollisionShape> shapes,
                const Eigen::Isometry3d& T_tool_object);
  // Holds the workspace object `name` where it is at configuration q (its pose relative to
  // the tool then). Errors: no such object.
  Status attach_object(const std::string& name, const Eigen::VectorXd& q,
                       double gripper_fraction = 0.5);

  CollisionReport check(const Eigen::VectorXd& q, double gripper_fraction = 0.5);

  // For continuous checking: pose every body at (q, f), then query single pairs.
  void set_configuration(const Eigen::VectorXd& q, double gripper_fraction);
  // With relative_error > 0 a mesh's search stops early: distance_m is then a distance between
  // two points of the shapes (>= the true one) and lower_bound_m = distance_m /
  // (1 + relative_error) <= the true one. Primitives and convex hulls are always exact
  // (lower_bound_m = distance_m when neither side has a bounding-volume tree).
  PairDistance distance(const CollisionPair& pair, double relative_error = 0.0);
  // A cheap lower bound on the pair's distance at the configuration set: the distance between
  // the two sides' axis-aligned bounds in the base frame (0 when they overlap), no FCL query.
  double distance_lower_bound(const CollisionPair& pair);
  bool in_contact(const CollisionPair& pair);
  // Penetration depth of a pair in contact (0 when not, or when FCL gives none).
  double penetration_depth(const CollisionPair& pair, Eigen::Vector3d* point_base = nullptr);

  // The naive baseline (benchmarks): every pair's distance at the configuration set, no
  // bounds culling; returns the smallest (contacts count as <= 0).
  double min_distance_all_pairs();

 private:
  struct Impl;
  explicit CollisionChecker(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

// How the robot's mesh shapes are checked (docs/collision.md, "Performance"):
//   kConvexParts  the convex hulls of their connected parts (convex_hull.hpp), each part a
//                 body of the link's name (split_into_parts), by GJK: a few microseconds a
//                 query instead of ~100 (a 10 s ur6 plan 25x faster, docs/benchmarks.md);
//                 conservative (a hull contains its part: distances can only be smaller,
//                 contacts only more). The default: it keeps validation interactive and errs
//                 on the safe side by at most 1.4 mm on the shipped arms, well inside the
//                 centimetre safety margins.
//   kExact        their triangles, through an OBBRSS bounding-volume tree: for a mesh with
//                 deep concavities the hulls would fill in (`--exact-meshes` on the CLI).
enum class MeshCollision { kExact, kConvexParts };

struct CollisionSetupOptions {
  GeometryOptions geometry;         // meshes of a URDF robot's links
  AllowedCollisionOptions allowed;  // how the allowed-collision matrix is computed
  MeshCollision mesh_collision = MeshCollision::kConvexParts;
};

// The checker for a robot description in a workspace (meshes loaded): the robot's bodies and
// its allowed-collision matrix: the robot file's `allowed_collisions:` (plus the adjacent
// pairs) when it stores one, else computed (compute_allowed_collisions).
Result<CollisionChecker> make_collision_checker(const core::RobotDescription& description,
                                                const core::Workspace& workspace,
                                                const CollisionSetupOptions& options = {});

}  // namespace telear::geometry
