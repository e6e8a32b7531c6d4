#pragma once
// A robot's visual body and collision geometry, built once from its URDF description.
//
// Visual body (body_for): the chain has frames 0..n; every URDF link rides on one frame
// (core::RobotDescription). Frame k's part is ONE mesh: the visuals of every rigid link on
// frame k, each moved into frame k by T_frame_link, merged (one vertex buffer per frame, the
// seed's per-link object). A link that moves with the gripper becomes a moving part: its
// visuals in its own link frame, posed at draw time by its attachment steps evaluated at the
// gripper opening (core::ArmBodyPose moves matrices only). A DH robot (no URDF links) gets
// core::body_description_for; a robot file's `body:` override is loaded instead of the URDF.
//
// Missing meshes: MissingMeshes::kError (default) fails naming the link, URI and the places
// looked; kPrimitives draws a stand-in instead and adds a warning: the link's collision
// primitives when it has any, else a small sphere at the visual's origin.
//
// Collision geometry (collision_geometry_for): per link its <collision> shapes, primitives
// kept as primitives and meshes loaded; a link without <collision> falls back to its
// <visual> shapes (from_visual), the usual convention of URDF tools.

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "telear/core/arm_body.hpp"
#include "telear/core/mesh.hpp"
#include "telear/core/result.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/geometry/mesh_file.hpp"

namespace telear::geometry {

enum class MissingMeshes { kError, kPrimitives };

constexpr double kStandInSphereRadius_m = 0.02;

struct GeometryOptions {
  std::vector<std::string> package_paths;  // --package-path, searched first
  // ROS_PACKAGE_PATH's entries; unset: read from the environment.
  std::optional<std::vector<std::string>> ros_package_path;
  MissingMeshes missing_meshes = MissingMeshes::kError;
  MeshLimits limits;
  int segments = 24;  // cylinders and spheres of URDF primitives (>= 3)
  double feature_angle_deg = 30.0;
  // Visual meshes from files are drawn at this level of detail (mesh_simplification.hpp):
  // edges collapse while the surface moves at most this far (metres; 0: as loaded). Half a
  // millimetre is ~0.1 px at the rigs' 2 m and 530 px focal length. Collision meshes are
  // never simplified (a simplified surface may cut inside the link).
  double visual_tolerance_m = 0.0005;

  Status validate() const;  // names the field and the constraint
};

struct RobotBody {
  core::BodyDescription body;
  std::vector<std::string> warnings;     // stand-ins drawn for missing meshes
  std::size_t mesh_file_triangles = 0;   // triangles of the visual mesh files as loaded
  std::size_t drawn_mesh_triangles = 0;  // the same after the level of detail
};

// The mesh of one URDF primitive (box, cylinder along z of URDF length, sphere) in its
// link's frame (T_link_geometry applied).
core::Mesh primitive_mesh(const core::GeometryElement& element, const Eigen::Vector3f& colour,
                          int segments);

Result<RobotBody> body_for(const core::RobotDescription& description,
                           const GeometryOptions& options = {});

struct CollisionShape {
  core::GeometryElement::Kind kind = core::GeometryElement::Kind::kBox;
  Eigen::Isometry3d T_link_shape = Eigen::Isometry3d::Identity();
  Eigen::Vector3d box_size = Eigen::Vector3d::Zero();  // m, full size
  double radius = 0.0;                                 // cylinder, sphere (m)
  double length = 0.0;                                 // cylinder (m), along z
  core::Mesh mesh;                                     // kMesh: scaled, in the shape frame
  // kMesh: the mesh is a convex hull (convex_hull.hpp), checked as a convex polytope (GJK)
  // instead of through a bounding-volume tree of its triangles.
  bool convex = false;
};

struct LinkCollision {
  std::string link;
  std::size_t link_index = 0;  // into RobotDescription::links
  int frame = 0;               // the chain frame it rides on
  bool from_visual = false;    // no <collision>: the visuals stand in
  std::vector<CollisionShape> shapes;
};

struct RobotCollisionGeometry {
  std::vector<LinkCollision> links;  // links with at least one shape, in description order
  std::vector<std::string> warnings;
};

Result<RobotCollisionGeometry> collision_geometry_for(const core::RobotDescription& description,
                                                      const GeometryOptions& options = {});

}  // namespace telear::geometry
