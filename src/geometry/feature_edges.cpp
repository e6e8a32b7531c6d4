#include "telear/geometry/feature_edges.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "telear/core/angles.hpp"

namespace telear::geometry {
namespace {

struct EdgeUse {
  std::uint32_t a = 0, b = 0;  // vertex indices of the first triangle using the edge
  int count = 0;
  Eigen::Vector3f normal0 = Eigen::Vector3f::Zero();
  bool crease = false;
};

Eigen::Vector3f position(const core::Mesh& m, std::uint32_t i) {
  const core::MeshVertex& v = m.vertices[i];
  return {v.position[0], v.position[1], v.position[2]};
}

}  // namespace

void set_feature_edges(core::Mesh& mesh, double angle_deg) {
  mesh.lines.clear();
  if (mesh.vertices.empty()) return;
  // Weld by position on a grid of 1e-6 of the mesh's extent.
  Eigen::Vector3f lo = position(mesh, 0), hi = lo;
  for (std::uint32_t i = 0; i < mesh.vertices.size(); ++i) {
    lo = lo.cwiseMin(position(mesh, i));
    hi = hi.cwiseMax(position(mesh, i));
  }
  const float cell = std::max(1e-6f * (hi - lo).maxCoeff(), 1e-12f);
  std::unordered_map<std::uint64_t, std::uint32_t> grid;
  std::vector<std::uint32_t> weld(mesh.vertices.size());
  for (std::uint32_t i = 0; i < mesh.vertices.size(); ++i) {
    const Eigen::Vector3f q = ((position(mesh, i) - lo) / cell).array().round();
    // 21 bits per axis: 2^21 cells per axis exceeds 1 / 1e-6.
    const std::uint64_t key = (static_cast<std::uint64_t>(q.x()) << 42) |
                              (static_cast<std::uint64_t>(q.y()) << 21) |
                              static_cast<std::uint64_t>(q.z());
    weld[i] = grid.emplace(key, static_cast<std::uint32_t>(grid.size())).first->second;
  }

  const float cos_limit = static_cast<float>(std::cos(core::radians_from_degrees(angle_deg)));
  std::unordered_map<std::uint64_t, EdgeUse> edges;
  std::vector<std::uint64_t> order;  // first-seen order keeps the line list deterministic
  for (std::size_t t = 0; t + 2 < mesh.triangles.size(); t += 3) {
    const std::uint32_t v[3] = {mesh.triangles[t], mesh.triangles[t + 1], mesh.triangles[t + 2]};
    const Eigen::Vector3f n = (position(mesh, v[1]) - position(mesh, v[0]))
                                  .cross(position(mesh, v[2]) - position(mesh, v[0]));
    if (n.norm() <= 0.0f) continue;
    const Eigen::Vector3f unit = n.normalized();
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = v[k], b = v[(k + 1) % 3];
      const std::uint32_t wa = weld[a], wb = weld[b];
      if (wa == wb) continue;
      const std::uint64_t key =
          (static_cast<std::uint64_t>(std::min(wa, wb)) << 32) | std::max(wa, wb);
      auto [it, inserted] = edges.try_emplace(key);
      EdgeUse& e = it->second;
      if (inserted) {
        e.a = a;
        e.b = b;
        e.normal0 = unit;
        order.push_back(key);
      } else if (e.count == 1 && unit.dot(e.normal0) < cos_limit) {
        e.crease = true;
      }
      ++e.count;
    }
  }
  for (std::uint64_t key : order) {
    const EdgeUse& e = edges[key];
    if (e.count != 2 || e.crease) mesh.lines.insert(mesh.lines.end(), {e.a, e.b});
  }
}

}  // namespace telear::geometry
