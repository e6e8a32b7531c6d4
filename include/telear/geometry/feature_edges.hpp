#pragma once
// The wire-frame of a loaded mesh: its feature edges, not every triangle edge.
//
// Triangles are joined by position (vertices closer than 1e-6 of the mesh's size are one
// point, so an STL's unshared corners still meet). An edge is a feature edge when
//   - one triangle uses it (a boundary: an open mesh's rim), or
//   - more than two do (non-manifold), or
//   - two do and their face normals differ by more than `angle_deg` (the dihedral crease):
//     n0 . n1 < cos(angle_deg).
// A cube in 12 triangles has 18 edges, of which the 6 face diagonals are flat: 12 lines.
// Degenerate (zero-area) triangles take no part.

#include "telear/core/mesh.hpp"

namespace telear::geometry {

constexpr double kDefaultFeatureAngleDeg = 30.0;

// Replaces mesh.lines with the feature edges (indices of the vertices of the first triangle
// that uses each edge).
void set_feature_edges(core::Mesh& mesh, double angle_deg = kDefaultFeatureAngleDeg);

}  // namespace telear::geometry
