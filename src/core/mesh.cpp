#include "telear/core/mesh.hpp"

#include <Eigen/Geometry>
#include <cassert>
#include <cmath>

namespace telear::core {
namespace {

constexpr float kTwoPiFloat = 6.28318530717958647692f;

// Two unit vectors completing `axis` to a right-handed orthonormal basis (u, v, axis).
void orthonormal_basis(const Eigen::Vector3f& axis, Eigen::Vector3f& u, Eigen::Vector3f& v) {
  const Eigen::Vector3f helper =
      std::abs(axis.x()) < 0.9f ? Eigen::Vector3f::UnitX() : Eigen::Vector3f::UnitY();
  u = helper.cross(axis).normalized();
  v = axis.cross(u);
}

// One planar quad a b c d (counter-clockwise seen from outside) with its own four vertices.
void append_quad(Mesh& mesh, const Eigen::Vector3f& a, const Eigen::Vector3f& b,
                 const Eigen::Vector3f& c, const Eigen::Vector3f& d,
                 const Eigen::Vector3f& colour) {
  const Eigen::Vector3f n = (b - a).cross(d - a).normalized();
  const std::uint32_t i0 = mesh.add_vertex(a, n, colour);
  const std::uint32_t i1 = mesh.add_vertex(b, n, colour);
  const std::uint32_t i2 = mesh.add_vertex(c, n, colour);
  const std::uint32_t i3 = mesh.add_vertex(d, n, colour);
  mesh.append_triangle_fan({i0, i1, i2, i3});
}

// Six flat faces of a hexahedron with corners c[0..3] around the start face and c[4..7]
// around the end face, each in the order (-w,-h) (+w,-h) (+w,+h) (-w,+h) of a right-handed
// (w, h, axis) basis; 24 vertices so that every face has its own normal.
void append_hexahedron(Mesh& mesh, const Eigen::Vector3f (&c)[8], const Eigen::Vector3f& colour) {
  // Faces counter-clockwise seen from outside (axis = corner 0 -> corner 4 direction).
  append_quad(mesh, c[0], c[3], c[2], c[1], colour);  // start cap (facing -axis)
  append_quad(mesh, c[4], c[5], c[6], c[7], colour);  // end cap (facing +axis)
  append_quad(mesh, c[0], c[1], c[5], c[4], colour);  // -h side
  append_quad(mesh, c[1], c[2], c[6], c[5], colour);  // +w side
  append_quad(mesh, c[2], c[3], c[7], c[6], colour);  // +h side
  append_quad(mesh, c[3], c[0], c[4], c[7], colour);  // -w side
}

}  // namespace

std::uint32_t Mesh::add_vertex(const Eigen::Vector3f& position, const Eigen::Vector3f& normal,
                               const Eigen::Vector3f& colour) {
  MeshVertex v{};
  for (int k = 0; k < 3; ++k) {
    v.position[k] = position[k];
    v.normal[k] = normal[k];
    v.colour[k] = colour[k];
  }
  vertices.push_back(v);
  return static_cast<std::uint32_t>(vertices.size() - 1);
}

void Mesh::append(const Mesh& other) {
  const auto base = static_cast<std::uint32_t>(vertices.size());
  vertices.insert(vertices.end(), other.vertices.begin(), other.vertices.end());
  for (std::uint32_t i : other.triangles) triangles.push_back(base + i);
  for (std::uint32_t i : other.lines) lines.push_back(base + i);
}

void Mesh::append_triangle_strip(const std::vector<std::uint32_t>& strip) {
  for (std::size_t k = 2; k < strip.size(); ++k) {
    // Triangle k-2 of a strip is (k-2, k-1, k) for even k-2 and (k-1, k-2, k) for odd, so
    // that all of them keep the first triangle's winding (GL's rule for strips).
    if ((k - 2) % 2 == 0) {
      triangles.insert(triangles.end(), {strip[k - 2], strip[k - 1], strip[k]});
    } else {
      triangles.insert(triangles.end(), {strip[k - 1], strip[k - 2], strip[k]});
    }
  }
}

void Mesh::append_triangle_fan(const std::vector<std::uint32_t>& fan) {
  for (std::size_t k = 2; k < fan.size(); ++k) {
    triangles.insert(triangles.end(), {fan[0], fan[k - 1], fan[k]});
  }
}

void Mesh::transform(const Eigen::Matrix4f& T) {
  const Eigen::Matrix3f R = T.topLeftCorner<3, 3>();
  const Eigen::Vector3f t = T.topRightCorner<3, 1>();
  for (MeshVertex& v : vertices) {
    const Eigen::Vector3f p = R * Eigen::Vector3f(v.position[0], v.position[1], v.position[2]) + t;
    const Eigen::Vector3f n = R * Eigen::Vector3f(v.normal[0], v.normal[1], v.normal[2]);
    for (int k = 0; k < 3; ++k) {
      v.position[k] = p[k];
      v.normal[k] = n[k];
    }
  }
}

void append_cylinder(Mesh& mesh, const Eigen::Vector3f& p0, const Eigen::Vector3f& p1, float radius,
                     int segments, const Eigen::Vector3f& colour) {
  assert(segments >= kMinCylinderSegments && "append_cylinder(): fewer than 3 segments");
  assert(radius > 0.0f && "append_cylinder(): radius must be positive");
  assert((p1 - p0).norm() > 0.0f && "append_cylinder(): p0 == p1");
  const Eigen::Vector3f axis = (p1 - p0).normalized();
  Eigen::Vector3f u, v;
  orthonormal_basis(axis, u, v);
  const auto n = static_cast<std::size_t>(segments);

  // Wall: one strip p0-ring / p1-ring, N + 1 columns (the seam is duplicated so the strip
  // closes), radial normals.
  std::vector<std::uint32_t> strip;
  strip.reserve(2 * (n + 1));
  std::vector<Eigen::Vector3f> ring(n);
  for (std::size_t k = 0; k <= n; ++k) {
    const float angle = kTwoPiFloat * static_cast<float>(k % n) / static_cast<float>(segments);
    const Eigen::Vector3f radial = std::cos(angle) * u + std::sin(angle) * v;
    if (k < n) ring[k] = radial;
    // (p1, p0) order makes the strip counter-clockwise seen from outside.
    strip.push_back(mesh.add_vertex(p1 + radius * radial, radial, colour));
    strip.push_back(mesh.add_vertex(p0 + radius * radial, radial, colour));
  }
  mesh.append_triangle_strip(strip);

  // Caps: a fan around each centre, N rim vertices, axial normals. The p1 cap turns
  // counter-clockwise about +axis; the p0 cap the other way.
  std::vector<std::uint32_t> fan1{mesh.add_vertex(p1, axis, colour)};
  std::vector<std::uint32_t> fan0{mesh.add_vertex(p0, -axis, colour)};
  std::uint32_t first1 = 0, first0 = 0;
  for (std::size_t k = 0; k < n; ++k) {
    fan1.push_back(mesh.add_vertex(p1 + radius * ring[k], axis, colour));
    if (k == 0) first1 = fan1.back();
  }
  for (std::size_t k = 0; k < n; ++k) {
    fan0.push_back(mesh.add_vertex(p0 + radius * ring[(n - k) % n], -axis, colour));
    if (k == 0) first0 = fan0.back();
  }
  fan1.push_back(first1);  // close the fan: N triangles over N + 2 indices
  fan0.push_back(first0);
  mesh.append_triangle_fan(fan1);
  mesh.append_triangle_fan(fan0);

  // Wire-frame: both rims and the N generators (wall columns 0..N-1).
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint32_t a1 = fan1[1 + k], b1 = fan1[1 + (k + 1) % n];
    mesh.lines.insert(mesh.lines.end(), {a1, b1});
    const std::uint32_t a0 = fan0[1 + k], b0 = fan0[1 + (k + 1) % n];
    mesh.lines.insert(mesh.lines.end(), {a0, b0});
    mesh.lines.insert(mesh.lines.end(), {strip[2 * k], strip[2 * k + 1]});
  }
}

void append_tapered_box(Mesh& mesh, const Eigen::Vector3f& p0, const Eigen::Vector3f& p1,
                        const Eigen::Vector2f& size0, const Eigen::Vector2f& size1,
                        const Eigen::Vector3f& up, const Eigen::Vector3f& colour) {
  assert((p1 - p0).norm() > 0.0f && "append_tapered_box(): p0 == p1");
  const Eigen::Vector3f axis = (p1 - p0).normalized();
  const Eigen::Vector3f h = (up - up.dot(axis) * axis).normalized();  // height direction
  assert(h.allFinite() && "append_tapered_box(): up is parallel to the axis");
  const Eigen::Vector3f w = h.cross(axis);  // (w, h, axis) right-handed
  Eigen::Vector3f c[8];
  const Eigen::Vector2f s0 = size0 / 2, s1 = size1 / 2;
  c[0] = p0 - s0.x() * w - s0.y() * h;
  c[1] = p0 + s0.x() * w - s0.y() * h;
  c[2] = p0 + s0.x() * w + s0.y() * h;
  c[3] = p0 - s0.x() * w + s0.y() * h;
  c[4] = p1 - s1.x() * w - s1.y() * h;
  c[5] = p1 + s1.x() * w - s1.y() * h;
  c[6] = p1 + s1.x() * w + s1.y() * h;
  c[7] = p1 - s1.x() * w + s1.y() * h;
  const auto first = static_cast<std::uint32_t>(mesh.vertices.size());
  append_hexahedron(mesh, c, colour);
  // Vertices first+0..3 are the start cap c0 c3 c2 c1, first+4..7 the end cap c4 c5 c6 c7.
  const std::uint32_t s[4] = {first + 0, first + 3, first + 2, first + 1};  // c0 c1 c2 c3
  const std::uint32_t e[4] = {first + 4, first + 5, first + 6, first + 7};  // c4 c5 c6 c7
  for (int k = 0; k < 4; ++k) {
    mesh.lines.insert(mesh.lines.end(), {s[k], s[(k + 1) % 4]});
    mesh.lines.insert(mesh.lines.end(), {e[k], e[(k + 1) % 4]});
    mesh.lines.insert(mesh.lines.end(), {s[k], e[k]});
  }
}

void append_box(Mesh& mesh, const Eigen::Vector3f& centre, const Eigen::Vector3f& size,
                const Eigen::Vector3f& colour) {
  const Eigen::Vector3f half = size / 2;
  const Eigen::Vector3f p0 = centre - Eigen::Vector3f(0, 0, half.z());
  const Eigen::Vector3f p1 = centre + Eigen::Vector3f(0, 0, half.z());
  const Eigen::Vector2f xy(size.x(), size.y());
  append_tapered_box(mesh, p0, p1, xy, xy, Eigen::Vector3f::UnitY(), colour);
}

void append_sphere(Mesh& mesh, const Eigen::Vector3f& centre, float radius, int segments,
                   const Eigen::Vector3f& colour) {
  assert(segments >= kMinCylinderSegments && "append_sphere(): fewer than 3 segments");
  assert(radius > 0.0f && "append_sphere(): radius must be positive");
  const int n = segments, r = sphere_band_count(segments);
  const auto first = static_cast<std::uint32_t>(mesh.vertices.size());
  // Vertex (i, j): ring i = 0..R from the +z pole, column j = 0..N (N is the seam again).
  for (int i = 0; i <= r; ++i) {
    const float theta = 0.5f * kTwoPiFloat * static_cast<float>(i) / static_cast<float>(r);
    for (int j = 0; j <= n; ++j) {
      const float phi = kTwoPiFloat * static_cast<float>(j % n) / static_cast<float>(n);
      const Eigen::Vector3f d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                              std::cos(theta));
      mesh.add_vertex(centre + radius * d, d, colour);
    }
  }
  const auto at = [&](int i, int j) { return first + static_cast<std::uint32_t>(i * (n + 1) + j); };
  // Seen from outside, ring i + 1 is below ring i and column j + 1 right of column j, so
  // (a b c), (a c d) over a = (i, j), b = (i+1, j), c = (i+1, j+1), d = (i, j+1) are
  // counter-clockwise; the polar bands keep the one triangle that is not degenerate.
  for (int i = 0; i < r; ++i) {
    for (int j = 0; j < n; ++j) {
      const std::uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      if (i != r - 1) mesh.triangles.insert(mesh.triangles.end(), {a, b, c});
      if (i != 0) mesh.triangles.insert(mesh.triangles.end(), {a, c, d});
    }
  }
  for (int j = 0; j < n; ++j) mesh.lines.insert(mesh.lines.end(), {at(r / 2, j), at(r / 2, j + 1)});
  for (int j : {0, n / 2}) {
    for (int i = 0; i < r; ++i) mesh.lines.insert(mesh.lines.end(), {at(i, j), at(i + 1, j)});
  }
}

void append_checker_floor(Mesh& mesh, float size, int tiles, const Eigen::Vector3f& colour_a,
                          const Eigen::Vector3f& colour_b) {
  assert(tiles >= 1 && size > 0.0f && "append_checker_floor(): empty floor");
  const float step = size / static_cast<float>(tiles);
  const float start = -size / 2;
  const Eigen::Vector3f n = Eigen::Vector3f::UnitZ();
  for (int j = 0; j < tiles; ++j) {
    for (int i = 0; i < tiles; ++i) {
      const float x0 = start + step * static_cast<float>(i),
                  y0 = start + step * static_cast<float>(j);
      const Eigen::Vector3f& colour = (i + j) % 2 == 0 ? colour_a : colour_b;
      const std::uint32_t a = mesh.add_vertex({x0, y0, 0}, n, colour);
      const std::uint32_t b = mesh.add_vertex({x0 + step, y0, 0}, n, colour);
      const std::uint32_t c = mesh.add_vertex({x0 + step, y0 + step, 0}, n, colour);
      const std::uint32_t d = mesh.add_vertex({x0, y0 + step, 0}, n, colour);
      mesh.append_triangle_fan({a, b, c, d});
      mesh.lines.insert(mesh.lines.end(), {a, b, a, d});
      if (i == tiles - 1) mesh.lines.insert(mesh.lines.end(), {b, c});
      if (j == tiles - 1) mesh.lines.insert(mesh.lines.end(), {d, c});
    }
  }
}

}  // namespace telear::core
