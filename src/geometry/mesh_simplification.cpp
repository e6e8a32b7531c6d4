#include "telear/geometry/mesh_simplification.hpp"

#include <meshoptimizer.h>

#include "telear/geometry/feature_edges.hpp"

namespace telear::geometry {
namespace {
constexpr double kEstimateMargin = 0.5;
}  // namespace

SimplifiedMesh simplify_mesh(const core::Mesh& mesh, double max_deviation_m,
                             double feature_angle_deg) {
  SimplifiedMesh out;
  if (max_deviation_m <= 0.0 || mesh.triangles.empty()) {
    out.mesh = mesh;
    return out;
  }
  const float* positions = mesh.vertices.front().position;
  const std::size_t stride = sizeof(core::MeshVertex);
  const float scale = meshopt_simplifyScale(positions, mesh.vertices.size(), stride);
  if (!(scale > 0.0f)) {  // every vertex at one point: nothing to simplify
    out.mesh = mesh;
    return out;
  }
  std::vector<std::uint32_t> kept(mesh.triangles.size());
  float relative_error = 0.0f;
  // Target count 0: as few triangles as the error bound allows. The quadric error is an
  // estimate that runs below the true distance (1.7x on a sphere, tests/geometry), so the
  // simplifier gets half the tolerance and the measured deviation stays inside the whole.
  const float target_error = static_cast<float>(kEstimateMargin * max_deviation_m) / scale;
  const std::size_t count =
      meshopt_simplify(kept.data(), mesh.triangles.data(), mesh.triangles.size(), positions,
                       mesh.vertices.size(), stride, 0, target_error, 0, &relative_error);
  kept.resize(count);
  meshopt_optimizeVertexCache(kept.data(), kept.data(), kept.size(), mesh.vertices.size());
  out.mesh.vertices.resize(mesh.vertices.size());
  const std::size_t used =
      meshopt_optimizeVertexFetch(out.mesh.vertices.data(), kept.data(), kept.size(),
                                  mesh.vertices.data(), mesh.vertices.size(), stride);
  out.mesh.vertices.resize(used);
  out.mesh.triangles = std::move(kept);
  set_feature_edges(out.mesh, feature_angle_deg);
  out.estimated_deviation_m = static_cast<double>(relative_error) * scale;
  return out;
}

}  // namespace telear::geometry
