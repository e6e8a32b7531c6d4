#include "telear/geometry/robot_geometry.hpp"

#include <cmath>
#include <filesystem>

#include "telear/core/resource_uri.hpp"
#include "telear/geometry/mesh_simplification.hpp"

namespace telear::geometry {
namespace {

using core::GeometryElement;

core::ResourceSearchPaths search_paths(const core::RobotDescription& d, const GeometryOptions& o) {
  core::ResourceSearchPaths s;
  s.package_paths = o.package_paths;
  s.robot_package_paths = d.package_paths;
  s.ros_package_path =
      o.ros_package_path ? *o.ros_package_path : core::ros_package_path_from_environment();
  if (!d.urdf_path.empty()) s.base_dir = std::filesystem::path(d.urdf_path).parent_path().string();
  return s;
}

Eigen::Vector3f colour_of(const GeometryElement& e) {
  return e.rgba ? Eigen::Vector3f(e.rgba->head<3>()) : kDefaultMeshColour;
}

std::string link_prefix(const core::RobotLink& link) {
  return "link '" + link.name + "': ";
}

// A mesh that was found but not loaded: the link, the URI as the URDF wrote it, then the
// loader's reason, which names the file the URI resolved to.
std::string mesh_prefix(const core::RobotLink& link, const GeometryElement& e) {
  return link_prefix(link) + "mesh '" + e.mesh_uri + "': ";
}

// Primitive sizes must be positive: a zero box would assert in core's mesh builders.
Status check_primitive(const core::RobotLink& link, const GeometryElement& e) {
  const auto bad = [&](const std::string& what) { return Error{link_prefix(link) + what}; };
  switch (e.kind) {
    case GeometryElement::Kind::kBox:
      if (!(e.box_size.minCoeff() > 0.0) || !e.box_size.allFinite()) {
        return bad("box size must be positive on every axis");
      }
      break;
    case GeometryElement::Kind::kCylinder:
      if (!(e.radius > 0.0 && e.length > 0.0) || !std::isfinite(e.radius + e.length)) {
        return bad("cylinder radius and length must be positive");
      }
      break;
    case GeometryElement::Kind::kSphere:
      if (!(e.radius > 0.0) || !std::isfinite(e.radius))
        return bad("sphere radius must be positive");
      break;
    case GeometryElement::Kind::kMesh:
      break;
  }
  return Status::Ok();
}

// The file path of a mesh element; a not-found error is kept apart (the stand-in policy).
struct Resolved {
  std::optional<std::string> path;
  std::string not_found;  // the message when path is empty
};

Resolved resolve(const core::RobotLink& link, const GeometryElement& e,
                 const core::ResourceSearchPaths& s) {
  Result<std::string> path = core::resolve_resource_uri(e.mesh_uri, s);
  if (path) return {*path, {}};
  return {std::nullopt, link_prefix(link) + path.error().message};
}

MeshLoadOptions load_options(const GeometryElement& e, const GeometryOptions& o) {
  MeshLoadOptions m;
  m.scale = e.scale;
  m.rgba = e.rgba;
  m.limits = o.limits;
  m.feature_angle_deg = o.feature_angle_deg;
  return m;
}

// Stand-in for a missing visual mesh: the link's collision primitives, else a small sphere.
core::Mesh stand_in(const core::RobotLink& link, const GeometryElement& visual,
                    const GeometryOptions& o, std::string& what) {
  core::Mesh mesh;
  for (const GeometryElement& c : link.collisions) {
    if (c.kind == GeometryElement::Kind::kMesh || !check_primitive(link, c)) continue;
    mesh.append(primitive_mesh(c, colour_of(visual), o.segments));
  }
  if (!mesh.empty()) {
    what = "its collision primitives";
    return mesh;
  }
  GeometryElement sphere;
  sphere.kind = GeometryElement::Kind::kSphere;
  sphere.radius = kStandInSphereRadius_m;
  sphere.T_link_geometry.translation() = visual.T_link_geometry.translation();
  what = "a sphere";
  return primitive_mesh(sphere, colour_of(visual), o.segments);
}

// Every visual of `link` as one mesh in the link's frame.
Result<core::Mesh> visual_mesh(const core::RobotLink& link, const core::ResourceSearchPaths& search,
                               const GeometryOptions& o, RobotBody& body) {
  std::vector<std::string>& warnings = body.warnings;
  core::Mesh out;
  for (const GeometryElement& e : link.visuals) {
    if (e.kind != GeometryElement::Kind::kMesh) {
      if (Status s = check_primitive(link, e); !s) return s.error();
      out.append(primitive_mesh(e, colour_of(e), o.segments));
      continue;
    }
    const Resolved r = resolve(link, e, search);
    if (!r.path) {
      if (o.missing_meshes == MissingMeshes::kError) return Error{r.not_found};
      std::string what;
      out.append(stand_in(link, e, o, what));
      warnings.push_back(r.not_found + "; drawn as " + what);
      continue;
    }
    Result<core::Mesh> mesh = load_mesh_file(*r.path, load_options(e, o));
    if (!mesh) return Error{mesh_prefix(link, e) + mesh.error().message};
    SimplifiedMesh drawn = simplify_mesh(*mesh, o.visual_tolerance_m, o.feature_angle_deg);
    body.mesh_file_triangles += mesh->triangle_count();
    body.drawn_mesh_triangles += drawn.mesh.triangle_count();
    drawn.mesh.transform(e.T_link_geometry.matrix().cast<float>());
    out.append(drawn.mesh);
  }
  return out;
}

Status check_attachment(const core::RobotDescription& d, const core::RobotLink& link, int n) {
  if (link.frame < 0 || link.frame > n) {
    return Error{link_prefix(link) + "rides on frame " + std::to_string(link.frame) +
                 ", but the chain has frames 0.." + std::to_string(n)};
  }
  for (const core::AttachmentStep& step : link.steps) {
    if (step.gripper_joint < 0) continue;
    if (!d.gripper || static_cast<std::size_t>(step.gripper_joint) >= d.gripper->joints.size()) {
      return Error{link_prefix(link) + "moves with gripper joint " +
                   std::to_string(step.gripper_joint) + ", but the gripper has " +
                   std::to_string(d.gripper ? d.gripper->joints.size() : 0) + " joints"};
    }
  }
  return Status::Ok();
}

}  // namespace

Status GeometryOptions::validate() const {
  if (segments < core::kMinCylinderSegments) {
    return Error{"segments must be at least 3, got " + std::to_string(segments)};
  }
  if (!(visual_tolerance_m >= 0.0 && visual_tolerance_m <= 0.01)) {
    return Error{"visual_tolerance_m must be in [0, 0.01] m, got " +
                 std::to_string(visual_tolerance_m)};
  }
  MeshLoadOptions m;
  m.limits = limits;
  m.feature_angle_deg = feature_angle_deg;
  return m.validate();
}

core::Mesh primitive_mesh(const GeometryElement& e, const Eigen::Vector3f& colour, int segments) {
  core::Mesh mesh;
  switch (e.kind) {
    case GeometryElement::Kind::kBox:
      core::append_box(mesh, Eigen::Vector3f::Zero(), e.box_size.cast<float>(), colour);
      break;
    case GeometryElement::Kind::kCylinder: {
      const float half = static_cast<float>(e.length / 2);
      core::append_cylinder(mesh, {0, 0, -half}, {0, 0, half}, static_cast<float>(e.radius),
                            segments, colour);
      break;
    }
    case GeometryElement::Kind::kSphere:
      core::append_sphere(mesh, Eigen::Vector3f::Zero(), static_cast<float>(e.radius), segments,
                          colour);
      break;
    case GeometryElement::Kind::kMesh:
      assert(false && "primitive_mesh(): a mesh element is not a primitive");
      break;
  }
  mesh.transform(e.T_link_geometry.matrix().cast<float>());
  return mesh;
}

Result<RobotBody> body_for(const core::RobotDescription& d, const GeometryOptions& o) {
  if (Status s = o.validate(); !s) return s.error();
  if (!d.model) return Error{"robot '" + d.name + "' has no kinematic chain"};
  RobotBody out;
  if (!d.body_file.empty()) {
    Result<core::BodyDescription> body = core::load_body_yaml_file(d.body_file, *d.model);
    if (!body) return body.error();
    out.body = std::move(*body);
    return out;
  }
  if (d.links.empty()) {
    Result<core::BodyDescription> body = core::body_description_for(*d.model);
    if (!body) return body.error();
    out.body = std::move(*body);
    return out;
  }

  const int n = d.model->dof();
  const core::ResourceSearchPaths search = search_paths(d, o);
  core::BodyDescription& b = out.body;
  b.source = d.urdf_path.empty() ? d.source : d.urdf_path;
  b.default_segments = o.segments;
  b.links.resize(static_cast<std::size_t>(n) + 1);
  b.link_meshes.resize(static_cast<std::size_t>(n) + 1);
  for (std::size_t i = 0; i < d.links.size(); ++i) {
    const core::RobotLink& link = d.links[i];
    if (Status s = check_attachment(d, link, n); !s) return s.error();
    Result<core::Mesh> mesh = visual_mesh(link, search, o, out);
    if (!mesh) return mesh.error();
    if (mesh->empty()) continue;
    if (link.moves_with_gripper()) {
      core::MovingPartSpec part;
      part.name = link.name;
      part.link = link.frame;
      part.steps = link.steps;
      part.mesh = std::move(*mesh);
      b.moving_parts.push_back(std::move(part));
    } else {
      // Rigid on its frame: the steps are fixed, so any opening gives the same transform.
      mesh->transform(d.T_frame_link(i, 0.0).matrix().cast<float>());
      b.link_meshes[static_cast<std::size_t>(link.frame)].append(*mesh);
    }
  }
  b.gripper_joints = d.gripper;
  return out;
}

Result<RobotCollisionGeometry> collision_geometry_for(const core::RobotDescription& d,
                                                      const GeometryOptions& o) {
  if (Status s = o.validate(); !s) return s.error();
  RobotCollisionGeometry out;
  const core::ResourceSearchPaths search = search_paths(d, o);
  for (std::size_t i = 0; i < d.links.size(); ++i) {
    const core::RobotLink& link = d.links[i];
    LinkCollision lc;
    lc.link = link.name;
    lc.link_index = i;
    lc.frame = link.frame;
    lc.from_visual = link.collisions.empty();
    for (const GeometryElement& e : lc.from_visual ? link.visuals : link.collisions) {
      CollisionShape shape;
      shape.kind = e.kind;
      shape.T_link_shape = e.T_link_geometry;
      shape.box_size = e.box_size;
      shape.radius = e.radius;
      shape.length = e.length;
      if (e.kind != GeometryElement::Kind::kMesh) {
        if (Status s = check_primitive(link, e); !s) return s.error();
        lc.shapes.push_back(std::move(shape));
        continue;
      }
      const Resolved r = resolve(link, e, search);
      if (!r.path) {
        if (o.missing_meshes == MissingMeshes::kError) return Error{r.not_found};
        shape.kind = GeometryElement::Kind::kSphere;
        shape.radius = kStandInSphereRadius_m;
        out.warnings.push_back(r.not_found + "; a sphere stands in for its collision shape");
        lc.shapes.push_back(std::move(shape));
        continue;
      }
      Result<core::Mesh> mesh = load_mesh_file(*r.path, load_options(e, o));
      if (!mesh) return Error{mesh_prefix(link, e) + mesh.error().message};
      shape.mesh = std::move(*mesh);
      lc.shapes.push_back(std::move(shape));
    }
    if (!lc.shapes.empty()) out.links.push_back(std::move(lc));
  }
  return out;
}

}  // namespace telear::geometry
