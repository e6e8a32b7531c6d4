#include "telear/geometry/convex_hull.hpp"

#include <algorithm>
#include <map>
#include <numeric>
#include <set>
#include <utility>

namespace telear::geometry {
namespace {

struct Face {
  std::array<int, 3> v;
  Eigen::Vector3d normal;  // unit, outward
  double offset = 0.0;     // normal . p for p on the face
  bool alive = true;
};

Face make_face(const std::vector<Eigen::Vector3d>& p, int a, int b, int c) {
  Face f{{a, b, c}, (p[b] - p[a]).cross(p[c] - p[a]).normalized(), 0.0, true};
  f.offset = f.normal.dot(p[a]);
  return f;
}

// Union-find over vertex indices.
int root(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

Result<ConvexHull> convex_hull(const std::vector<Eigen::Vector3d>& points, double tolerance) {
  // Distinct points only (coincident ones would make zero-area faces).
  std::vector<Eigen::Vector3d> p;
  {
    std::set<std::array<double, 3>> seen;
    for (const Eigen::Vector3d& q : points) {
      if (seen.insert({q.x(), q.y(), q.z()}).second) p.push_back(q);
    }
  }
  if (p.size() < 4) return Error{"convex hull: fewer than 4 distinct points"};
  Eigen::Vector3d lo = p[0], hi = p[0];
  for (const Eigen::Vector3d& q : p) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
  const double eps = tolerance * std::max((hi - lo).norm(), 1e-300);

  // The first tetrahedron: two extreme points, the farthest from their line, the farthest
  // from their plane.
  const auto farthest = [&](auto&& distance) {
    int best = 0;
    double d = -1.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const double di = distance(p[i]);
      if (di > d) d = di, best = static_cast<int>(i);
    }
    return std::pair{best, d};
  };
  const int i0 = farthest([&](const Eigen::Vector3d& q) { return -q.x(); }).first;
  const auto [i1, d1] = farthest([&](const Eigen::Vector3d& q) { return (q - p[i0]).norm(); });
  const Eigen::Vector3d axis = (p[i1] - p[i0]) / std::max(d1, 1e-300);
  const auto [i2, d2] = farthest([&](const Eigen::Vector3d& q) {
    const Eigen::Vector3d r = q - p[i0];
    return (r - r.dot(axis) * axis).norm();
  });
  const Eigen::Vector3d n012 = (p[i1] - p[i0]).cross(p[i2] - p[i0]).normalized();
  const auto [i3, d3] =
      farthest([&](const Eigen::Vector3d& q) { return std::abs((q - p[i0]).dot(n012)); });
  if (d1 <= eps || d2 <= eps || d3 <= eps) {
    return Error{"convex hull: the points lie in a plane (no volume)"};
  }
  std::vector<Face> faces;
  const Eigen::Vector3d inside = (p[i0] + p[i1] + p[i2] + p[i3]) / 4.0;
  for (const std::array<int, 3>& t : {std::array{i0, i1, i2}, std::array{i0, i1, i3},
                                      std::array{i0, i2, i3}, std::array{i1, i2, i3}}) {
    Face f = make_face(p, t[0], t[1], t[2]);
    if (f.normal.dot(inside) > f.offset) f = make_face(p, t[0], t[2], t[1]);
    faces.push_back(f);
  }

  // Each point outside the hull so far replaces the faces it sees by a fan from the horizon
  // (the edges between faces it sees and faces it does not) to itself.
  std::vector<std::size_t> visible;
  std::set<std::pair<int, int>> edges;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const int pi = static_cast<int>(i);
    if (pi == i0 || pi == i1 || pi == i2 || pi == i3) continue;
    visible.clear();
    for (std::size_t f = 0; f < faces.size(); ++f) {
      if (faces[f].alive && faces[f].normal.dot(p[i]) - faces[f].offset > eps) visible.push_back(f);
    }
    if (visible.empty()) continue;  // inside (or on the surface within eps)
    edges.clear();
    for (std::size_t f : visible) {
      const std::array<int, 3>& v = faces[f].v;
      for (int k = 0; k < 3; ++k) edges.insert({v[k], v[(k + 1) % 3]});
      faces[f].alive = false;
    }
    for (const auto& [a, b] : edges) {
      if (edges.count({b, a})) continue;  // inner edge of the visible region
      faces.push_back(make_face(p, a, b, pi));
    }
  }

  // Compact: the vertices the live faces use.
  ConvexHull hull;
  std::map<int, int> index;
  for (const Face& f : faces) {
    if (!f.alive) continue;
    std::array<int, 3> t{};
    for (int k = 0; k < 3; ++k) {
      auto [it, added] = index.emplace(f.v[k], static_cast<int>(hull.vertices.size()));
      if (added) hull.vertices.push_back(p[static_cast<std::size_t>(f.v[k])]);
      t[k] = it->second;
    }
    hull.triangles.push_back(t);
  }
  return hull;
}

std::vector<std::vector<Eigen::Vector3d>> connected_parts(const core::Mesh& mesh) {
  // Vertices at the same position are one (an STL repeats them per triangle).
  std::map<std::array<float, 3>, int> by_position;
  std::vector<int> id(mesh.vertices.size());
  std::vector<Eigen::Vector3d> position;
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const auto& v = mesh.vertices[i].position;
    auto [it, added] = by_position.emplace(std::array<float, 3>{v[0], v[1], v[2]},
                                           static_cast<int>(position.size()));
    if (added) position.emplace_back(v[0], v[1], v[2]);
    id[i] = it->second;
  }
  std::vector<int> parent(position.size());
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<bool> used(position.size(), false);
  for (std::size_t t = 0; t + 2 < mesh.triangles.size(); t += 3) {
    const int a = id[mesh.triangles[t]];
    for (int k = 0; k < 3; ++k) {
      const int b = id[mesh.triangles[t + static_cast<std::size_t>(k)]];
      used[static_cast<std::size_t>(b)] = true;
      parent[static_cast<std::size_t>(root(parent, a))] = root(parent, b);
    }
  }
  std::map<int, std::size_t> part_of;
  std::vector<std::vector<Eigen::Vector3d>> parts;
  for (std::size_t i = 0; i < position.size(); ++i) {
    if (!used[i]) continue;
    auto [it, added] = part_of.emplace(root(parent, static_cast<int>(i)), parts.size());
    if (added) parts.emplace_back();
    parts[it->second].push_back(position[i]);
  }
  return parts;
}

Result<std::vector<CollisionShape>> convex_parts(const CollisionShape& shape) {
  if (shape.kind != core::GeometryElement::Kind::kMesh || shape.convex) return std::vector{shape};
  std::vector<CollisionShape> out;
  const std::vector<std::vector<Eigen::Vector3d>> parts = connected_parts(shape.mesh);
  for (std::size_t i = 0; i < parts.size(); ++i) {
    Result<ConvexHull> hull = convex_hull(parts[i]);
    if (!hull) return Error{"part " + std::to_string(i) + ": " + hull.error().message};
    CollisionShape part;
    part.kind = core::GeometryElement::Kind::kMesh;
    part.T_link_shape = shape.T_link_shape;
    part.convex = true;
    const Eigen::Vector3f none = Eigen::Vector3f::Zero();
    for (const Eigen::Vector3d& v : hull->vertices) {
      part.mesh.add_vertex(v.cast<float>(), none, none);
    }
    for (const std::array<int, 3>& t : hull->triangles) {
      for (int k : t) part.mesh.triangles.push_back(static_cast<std::uint32_t>(k));
    }
    out.push_back(std::move(part));
  }
  return out;
}

Status use_convex_parts(RobotCollisionModel& robot) {
  for (CollisionBody& body : robot.bodies) {
    std::vector<CollisionShape> shapes;
    for (const CollisionShape& shape : body.shapes) {
      Result<std::vector<CollisionShape>> parts = convex_parts(shape);
      if (!parts) return Error{"convex parts of '" + body.name + "': " + parts.error().message};
      for (CollisionShape& part : *parts) shapes.push_back(std::move(part));
    }
    body.shapes = std::move(shapes);
  }
  return Status::Ok();
}

void split_into_parts(RobotCollisionModel& robot) {
  std::vector<CollisionBody> bodies;
  for (CollisionBody& body : robot.bodies) {
    if (body.shapes.size() <= 1) {
      bodies.push_back(std::move(body));
      continue;
    }
    std::vector<CollisionShape> shapes = std::move(body.shapes);
    body.shapes.clear();
    for (CollisionShape& shape : shapes) {
      CollisionBody part = body;
      part.shapes = {std::move(shape)};
      bodies.push_back(std::move(part));
    }
  }
  robot.bodies = std::move(bodies);
  update_motion_bounds(robot);
}

}  // namespace telear::geometry
