#include "telear/geometry/collision_checker.hpp"

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "telear/core/kinematics.hpp"

namespace telear::geometry {
namespace {

using Kind = core::GeometryElement::Kind;
using GeometryPtr = std::shared_ptr<fcl::CollisionGeometryd>;

// A mesh as FCL's bounding-volume tree; OBBRSS answers both collision and distance queries.
GeometryPtr mesh_geometry(const core::Mesh& mesh) {
  auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  std::vector<fcl::Vector3d> points;
  points.reserve(mesh.vertices.size());
  for (const core::MeshVertex& v : mesh.vertices) {
    points.emplace_back(v.position[0], v.position[1], v.position[2]);
  }
  std::vector<fcl::Triangle> triangles;
  triangles.reserve(mesh.triangle_count());
  for (std::size_t t = 0; t + 2 < mesh.triangles.size(); t += 3) {
    triangles.emplace_back(mesh.triangles[t], mesh.triangles[t + 1], mesh.triangles[t + 2]);
  }
  model->beginModel(static_cast<int>(triangles.size()), static_cast<int>(points.size()));
  model->addSubModel(points, triangles);
  model->endModel();
  model->computeLocalAABB();
  return model;
}

// A convex hull (convex_hull.hpp) as FCL's convex polytope: distances by GJK.
GeometryPtr convex_geometry(const core::Mesh& mesh) {
  auto vertices = std::make_shared<std::vector<fcl::Vector3d>>();
  vertices->reserve(mesh.vertices.size());
  for (const core::MeshVertex& v : mesh.vertices) {
    vertices->emplace_back(v.position[0], v.position[1], v.position[2]);
  }
  auto faces = std::make_shared<std::vector<int>>();
  faces->reserve(mesh.triangles.size() / 3 * 4);
  for (std::size_t t = 0; t + 2 < mesh.triangles.size(); t += 3) {
    faces->push_back(3);
    for (std::size_t k = 0; k < 3; ++k) faces->push_back(static_cast<int>(mesh.triangles[t + k]));
  }
  auto convex =
      std::make_shared<fcl::Convexd>(vertices, static_cast<int>(mesh.triangle_count()), faces);
  convex->computeLocalAABB();
  return convex;
}

GeometryPtr fcl_geometry(const CollisionShape& s) {
  switch (s.kind) {
    case Kind::kBox:
      return std::make_shared<fcl::Boxd>(s.box_size.x(), s.box_size.y(), s.box_size.z());
    case Kind::kCylinder:
      return std::make_shared<fcl::Cylinderd>(s.radius, s.length);
    case Kind::kSphere:
      return std::make_shared<fcl::Sphered>(s.radius);
    case Kind::kMesh:
      return s.convex ? convex_geometry(s.mesh) : mesh_geometry(s.mesh);
  }
  return nullptr;
}

// A workspace object as a collision shape in its own frame.
Result<CollisionShape> shape_of(const core::WorkspaceObject& o) {
  CollisionShape s;
  switch (o.shape) {
    case core::ShapeKind::kBox:
      s.kind = Kind::kBox;
      s.box_size = o.size_m;
      break;
    case core::ShapeKind::kCylinder:
      s.kind = Kind::kCylinder;
      s.radius = o.radius_m;
      s.length = o.length_m;
      break;
    case core::ShapeKind::kSphere:
      s.kind = Kind::kSphere;
      s.radius = o.radius_m;
      break;
    case core::ShapeKind::kMesh:
      if (!o.mesh || o.mesh->triangles.empty()) {
        return Error{"object '" + o.name +
                     "': its mesh is not loaded (geometry::load_workspace_meshes)"};
      }
      s.kind = Kind::kMesh;
      s.mesh = *o.mesh;
      break;
  }
  return s;
}

}  // namespace

// Named, not file-local: CollisionChecker::Impl, which has linkage, holds Owners, and GCC warns
// about a field of file-local type in such a class (-Wsubobject-linkage) when this file is
// compiled as part of a unity batch.
namespace collision_checker_detail {

struct ShapeObject {
  Eigen::Isometry3d T_owner_shape = Eigen::Isometry3d::Identity();
  bool convex = false;  // a convex hull (see distance())
  std::unique_ptr<fcl::CollisionObjectd> object;
};

// A body or a workspace object: its shapes' FCL objects and their joint bounds.
struct Owner {
  std::vector<ShapeObject> shapes;
  fcl::AABBd aabb;
  bool active = true;
  bool exact = true;  // no bounding-volume tree: distances are never stopped early

  void add(const CollisionShape& s) {
    if (s.kind == Kind::kMesh && !s.convex) exact = false;
    ShapeObject so;
    so.T_owner_shape = s.T_link_shape;
    so.convex = s.kind == Kind::kMesh && s.convex;
    so.object = std::make_unique<fcl::CollisionObjectd>(fcl_geometry(s));
    shapes.push_back(std::move(so));
  }
  void set_pose(const Eigen::Isometry3d& T_base_owner) {
    for (std::size_t i = 0; i < shapes.size(); ++i) {
      ShapeObject& so = shapes[i];
      so.object->setTransform(T_base_owner * so.T_owner_shape);
      so.object->computeAABB();
      if (i == 0) {
        aabb = so.object->getAABB();
      } else {
        aabb += so.object->getAABB();
      }
    }
  }
};

}  // namespace collision_checker_detail

namespace {

using collision_checker_detail::Owner;
using collision_checker_detail::ShapeObject;

fcl::DistanceRequestd distance_request() {
  fcl::DistanceRequestd request;
  request.enable_nearest_points = true;
  request.enable_signed_distance = true;
  return request;
}

}  // namespace

struct CollisionChecker::Impl {
  RobotCollisionModel robot;
  AllowedCollisionMatrix allowed;
  core::Workspace workspace;
  std::vector<std::string> object_names;
  std::vector<Owner> bodies, objects;
  std::vector<CollisionPair> pairs;
  core::KinematicsData kin;
  double fraction = 0.5;
  std::vector<bool> dirty;  // per body: not posed at the current configuration yet
  fcl::DistanceRequestd request = distance_request();

  Impl(RobotCollisionModel r, const core::Workspace& w, AllowedCollisionMatrix a)
      : robot(std::move(r)), allowed(std::move(a)), workspace(w), kin(*robot.model) {}

  void build_pairs() {
    pairs.clear();
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      for (std::size_t o = 0; o < objects.size(); ++o) {
        if (objects[o].active) pairs.push_back({static_cast<int>(b), -1, static_cast<int>(o)});
      }
      for (std::size_t c = b + 1; c < bodies.size(); ++c) {
        // Parts of one link (split_into_parts) share its name: never checked one against the
        // other.
        if (robot.bodies[b].name == robot.bodies[c].name) continue;
        if (!allowed.allowed(robot.bodies[b].name, robot.bodies[c].name)) {
          pairs.push_back({static_cast<int>(b), static_cast<int>(c), -1});
        }
      }
    }
  }

  const Owner& other(const CollisionPair& p) const {
    return p.other_object >= 0 ? objects[static_cast<std::size_t>(p.other_object)]
                               : bodies[static_cast<std::size_t>(p.other_body)];
  }

  // Forward kinematics now; each body is posed when a query first needs it (continuous
  // checking re-computes a few pairs per step, so most bodies are not needed).
  void set_configuration(const Eigen::VectorXd& q, double f) {
    core::update_kinematics(*robot.model, kin, q);
    fraction = f;
    dirty.assign(bodies.size(), true);
  }

  Owner& body(std::size_t b) {
    if (dirty[b]) {
      bodies[b].set_pose(kin.T_base_link[static_cast<std::size_t>(robot.bodies[b].frame)] *
                         robot.T_frame_body(b, fraction));
      dirty[b] = false;
    }
    return bodies[b];
  }

  void pose_all() {
    for (std::size_t b = 0; b < bodies.size(); ++b) body(b);
  }

  Owner& other(const CollisionPair& p) {
    return p.other_object >= 0 ? objects[static_cast<std::size_t>(p.other_object)]
                               : body(static_cast<std::size_t>(p.other_body));
  }

  PairDistance distance(const CollisionPair& p, double relative_error) {
    PairDistance out;
    out.distance_m = std::numeric_limits<double>::infinity();
    const Owner& a = body(static_cast<std::size_t>(p.body));
    const Owner& b = other(p);
    fcl::DistanceRequestd r = request;
    // A volume is skipped when both its distance >= best - abs_err and its distance
    // * (1 + rel_err) >= best: abs_err unbounded leaves the relative test alone.
    r.rel_err = relative_error;
    r.abs_err = relative_error > 0.0 ? std::numeric_limits<double>::max() : 0.0;
    const bool several = a.shapes.size() * b.shapes.size() > 1;
    for (const ShapeObject& sa : a.shapes) {
      for (const ShapeObject& sb : b.shapes) {
        // Bounds apart by more than the nearest pair so far: cannot be nearer (bounds that
        // touch are always queried: a deeper penetration may hide there).
        if (several) {
          const fcl::AABBd& ba = sa.object->getAABB();
          const fcl::AABBd& bb = sb.object->getAABB();
          if (!ba.overlap(bb) && ba.distance(bb) >= out.distance_m) continue;
        }
        fcl::DistanceResultd result;
        // A hull goes to FCL's own GJK (libccd's distances to a Convex are off by up to a
        // millimetre), unsigned: its signed path needs a contact depth FCL may not give. In
        // contact it answers -1: 0 here (the depth is penetration_depth's).
        const bool convex = sa.convex || sb.convex;
        r.gjk_solver_type = convex ? fcl::GST_INDEP : fcl::GST_LIBCCD;
        r.enable_signed_distance = !convex;
        fcl::distance(sa.object.get(), sb.object.get(), r, result);
        if (convex && result.min_distance < 0.0) result.min_distance = 0.0;
        if (result.min_distance < out.distance_m) {
          out.distance_m = result.min_distance;
          out.p_body_base = result.nearest_points[0];
          out.p_other_base = result.nearest_points[1];
        }
      }
    }
    // FCL stops a bounding-volume tree's search once no volume can be nearer than the best
    // distance / (1 + rel_err): the true distance is at least that. Primitives and hulls are
    // exact.
    const bool exact = a.exact && b.exact;
    out.lower_bound_m =
        out.distance_m > 0.0 && !exact ? out.distance_m / (1.0 + relative_error) : out.distance_m;
    return out;
  }

  // Whether the pair is in contact and its deepest contact.
  bool collide(const CollisionPair& p, double& depth, Eigen::Vector3d& point) {
    const Owner& a = body(static_cast<std::size_t>(p.body));
    const Owner& b = other(p);
    bool hit = false;
    depth = 0.0;
    fcl::CollisionRequestd request(4, true);
    for (const ShapeObject& sa : a.shapes) {
      for (const ShapeObject& sb : b.shapes) {
        if (!sa.object->getAABB().overlap(sb.object->getAABB())) continue;
        fcl::CollisionResultd result;
        request.gjk_solver_type = sa.convex || sb.convex ? fcl::GST_INDEP : fcl::GST_LIBCCD;
        if (fcl::collide(sa.object.get(), sb.object.get(), request, result) == 0) continue;
        if (!hit) point = result.getContact(0).pos;
        hit = true;
        for (std::size_t i = 0; i < result.numContacts(); ++i) {
          const fcl::Contactd& c = result.getContact(i);
          // FCL's own GJK/EPA (GST_INDEP, the hulls' solver) reports the depth negated
          // (-epa.depth): the magnitude is the depth either way.
          const double d = std::abs(c.penetration_depth);
          if (d > depth) {
            depth = d;
            point = c.pos;
          }
        }
      }
    }
    return hit;
  }
};

CollisionChecker::CollisionChecker(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
CollisionChecker::CollisionChecker(CollisionChecker&&) noexcept = default;
CollisionChecker& CollisionChecker::operator=(CollisionChecker&&) noexcept = default;
CollisionChecker::~CollisionChecker() = default;

Result<CollisionChecker> CollisionChecker::create(RobotCollisionModel robot,
                                                  const core::Workspace& workspace,
                                                  AllowedCollisionMatrix allowed) {
  auto impl = std::make_unique<Impl>(std::move(robot), workspace, std::move(allowed));
  for (const CollisionBody& body : impl->robot.bodies) {
    Owner owner;
    for (const CollisionShape& s : body.shapes) owner.add(s);
    impl->bodies.push_back(std::move(owner));
  }
  for (const core::WorkspaceObject& o : workspace.objects) {
    Result<CollisionShape> shape = shape_of(o);
    if (!shape) {
      return Error{(workspace.source.empty() ? "" : workspace.source + ": ") +
                   shape.error().message};
    }
    Owner owner;
    owner.add(*shape);
    owner.set_pose(o.T_base_object);
    impl->objects.push_back(std::move(owner));
    impl->object_names.push_back(o.name);
  }
  impl->build_pairs();
  impl->set_configuration(Eigen::VectorXd::Zero(impl->robot.model->dof()), 0.5);
  return CollisionChecker(std::move(impl));
}

const RobotCollisionModel& CollisionChecker::robot() const {
  return impl_->robot;
}
const AllowedCollisionMatrix& CollisionChecker::allowed() const {
  return impl_->allowed;
}
const std::vector<std::string>& CollisionChecker::object_names() const {
  return impl_->object_names;
}
const std::vector<CollisionPair>& CollisionChecker::pairs() const {
  return impl_->pairs;
}

std::string CollisionChecker::pair_other_name(const CollisionPair& p) const {
  return p.other_object >= 0 ? impl_->object_names[static_cast<std::size_t>(p.other_object)]
                             : impl_->robot.bodies[static_cast<std::size_t>(p.other_body)].name;
}

Status CollisionChecker::attach(const std::string& name, std::vector<CollisionShape> shapes,
                                const Eigen::Isometry3d& T_tool_object) {
  Impl& m = *impl_;
  if (m.robot.body_index(name) >= 0) {
    return Error{"attach: the robot already has a body named '" + name + "'"};
  }
  if (shapes.empty()) return Error{"attach: object '" + name + "' has no shapes"};
  const std::size_t index = m.robot.attach(name, std::move(shapes), T_tool_object);
  Owner owner;
  for (const CollisionShape& s : m.robot.bodies[index].shapes) owner.add(s);
  m.bodies.push_back(std::move(owner));
  m.dirty.push_back(true);
  // The hand holds it: the bodies on the tip's frame may touch it (adjacency by frame).
  const int tip_frame = m.robot.bodies[index].frame;
  for (std::size_t b = 0; b < index; ++b) {
    if (std::abs(m.robot.bodies[b].frame - tip_frame) <= 1) {
      m.allowed.allow(name, m.robot.bodies[b].name, AllowedReason::kAdjacent);
    }
  }
  for (std::size_t o = 0; o < m.object_names.size(); ++o) {
    if (m.object_names[o] == name) m.objects[o].active = false;
  }
  m.build_pairs();
  m.set_configuration(m.kin.q, 0.5);
  return Status::Ok();
}

Status CollisionChecker::attach_object(const std::string& name, const Eigen::VectorXd& q,
                                       double gripper_fraction) {
  const core::WorkspaceObject* object = impl_->workspace.find(name);
  if (!object) return Error{"attach: the workspace has no object named '" + name + "'"};
  Result<CollisionShape> shape = shape_of(*object);
  if (!shape) return shape.error();
  if (Status s = core::check_joint_vector(*impl_->robot.model, q); !s) return s;
  impl_->set_configuration(q, gripper_fraction);
  const Eigen::Isometry3d T_tool_object = impl_->kin.T_base_tool.inverse() * object->T_base_object;
  return attach(name, {*shape}, T_tool_object);
}

void CollisionChecker::set_configuration(const Eigen::VectorXd& q, double gripper_fraction) {
  impl_->set_configuration(q, gripper_fraction);
}

PairDistance CollisionChecker::distance(const CollisionPair& pair, double relative_error) {
  return impl_->distance(pair, relative_error);
}

double CollisionChecker::distance_lower_bound(const CollisionPair& pair) {
  const Owner& a = impl_->body(static_cast<std::size_t>(pair.body));
  const Owner& b = impl_->other(pair);
  return a.aabb.overlap(b.aabb) ? 0.0 : a.aabb.distance(b.aabb);
}

bool CollisionChecker::in_contact(const CollisionPair& pair) {
  double depth = 0.0;
  Eigen::Vector3d p;
  return impl_->collide(pair, depth, p);
}

double CollisionChecker::penetration_depth(const CollisionPair& pair, Eigen::Vector3d* point) {
  double depth = 0.0;
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  impl_->collide(pair, depth, p);
  if (point) *point = p;
  return depth;
}

double CollisionChecker::min_distance_all_pairs() {
  double best = std::numeric_limits<double>::infinity();
  for (const CollisionPair& p : impl_->pairs) {
    best = std::min(best, impl_->distance(p, 0.0).distance_m);
  }
  return best;
}

CollisionReport CollisionChecker::check(const Eigen::VectorXd& q, double gripper_fraction) {
  Impl& m = *impl_;
  m.set_configuration(q, gripper_fraction);
  m.pose_all();
  CollisionReport report;
  // Contacts first (pairs whose bounds overlap), then clearance over the rest, nearest bounds
  // first so that most pairs are skipped by their bounds' distance.
  std::vector<std::pair<double, std::size_t>> by_bounds;
  for (std::size_t i = 0; i < m.pairs.size(); ++i) {
    const CollisionPair& p = m.pairs[i];
    const fcl::AABBd& a = m.bodies[static_cast<std::size_t>(p.body)].aabb;
    const fcl::AABBd& b = m.other(p).aabb;
    if (a.overlap(b)) {
      double depth = 0.0;
      Eigen::Vector3d point;
      if (m.collide(p, depth, point)) {
        // One contact per link pair (a link split into parts may touch with several).
        const std::string& body = m.robot.bodies[static_cast<std::size_t>(p.body)].name;
        const std::string other = pair_other_name(p);
        auto same =
            std::find_if(report.contacts.begin(), report.contacts.end(),
                         [&](const Contact& c) { return c.body == body && c.other == other; });
        if (same == report.contacts.end()) {
          report.contacts.push_back({body, other, p.other_body >= 0, depth, point});
        } else if (depth > same->depth_m) {
          same->depth_m = depth;
          same->point_base = point;
        }
        continue;
      }
      by_bounds.emplace_back(0.0, i);
    } else {
      by_bounds.emplace_back(a.distance(b), i);
    }
  }
  std::sort(by_bounds.begin(), by_bounds.end());
  Clearance& best = report.min_clearance;
  for (const auto& [bound, i] : by_bounds) {
    if (bound >= best.distance_m) break;
    const CollisionPair& p = m.pairs[i];
    const PairDistance d = m.distance(p, 0.0);
    if (d.distance_m < best.distance_m) {
      best.distance_m = std::max(d.distance_m, 0.0);
      best.body = m.robot.bodies[static_cast<std::size_t>(p.body)].name;
      best.other = pair_other_name(p);
      best.self = p.other_body >= 0;
      best.p_body_base = d.p_body_base;
      best.p_other_base = d.p_other_base;
    }
  }
  return report;
}

}  // namespace telear::geometry
