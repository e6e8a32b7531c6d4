#pragma once
// A lighter copy of a fine visual mesh for drawing: a level of detail chosen by a distance.
//
// Why: a lab's URDF meshes are made for print-quality renders (100k+ triangles per arm) and
// the software rasterizer of a headless machine spends its time on triangle set-up, not
// pixels (docs/benchmarks.md, "Render: a URDF mesh arm"). At the cameras' distance a
// deviation of half a millimetre is a tenth of a pixel, so most of those triangles change
// nothing a viewer can see.
//
// Method: meshoptimizer's edge-collapse simplifier (meshopt_simplify, quadric error metric,
// Debian's libmeshoptimizer-dev) collapses edges while its error estimate stays within
// `max_deviation_m` (metres, absolute: the tolerance is divided by meshopt_simplifyScale, the
// mesh's extent; half of it, as its estimate runs below the true distance). Vertices are only
// removed, never moved, so the kept ones keep their positions, normals and colours; seams where
// vertices share a position but not a normal (flat-shaded edges, STL's unshared corners) are kept
// as seams. The result is then ordered for the post-transform vertex cache
// (meshopt_optimizeVertexCache) and unused vertices are dropped (meshopt_optimizeVertexFetch); the
// wire-frame is recomputed from the remaining triangles (set_feature_edges).
//
// Guarantee: meshoptimizer's own estimate of the deviation (result_error x scale) is at most
// half of max_deviation_m; the tests measure the true deviation of a simplified sphere from
// the sphere and find it inside max_deviation_m (the estimate runs ~1.7x below the truth).

#include "telear/core/mesh.hpp"

namespace telear::geometry {

struct SimplifiedMesh {
  core::Mesh mesh;
  double estimated_deviation_m = 0.0;  // meshoptimizer's error estimate, metres
};

// max_deviation_m <= 0 returns the mesh as it is (no simplification, same order).
SimplifiedMesh simplify_mesh(const core::Mesh& mesh, double max_deviation_m,
                             double feature_angle_deg);

}  // namespace telear::geometry
