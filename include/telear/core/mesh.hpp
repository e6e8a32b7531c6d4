#pragma once
// Triangle meshes built on the CPU, in one rigid frame, for the arm body and scene objects.
//
// A Mesh is an indexed triangle list plus an indexed line list over one vertex array:
//
//   vertices   : V x MeshVertex, position (m), unit normal and diffuse RGB colour (0..1),
//                9 floats = 36 bytes each, tightly packed (the GPU vertex buffer layout);
//   triangles  : 3 T indices, counter-clockwise seen from outside (outward normals);
//   lines      : 2 L indices, the wire-frame: the shape's feature edges, not every diagonal.
//
// The primitives are built as the seed built them: a cylinder's wall is one triangle strip
// and each cap a triangle fan. GL 3.3 can draw strips and fans, but then every primitive is
// one draw call; the strip and fan index sequences are therefore expanded into the triangle
// list (append_triangle_strip / append_triangle_fan) so that a whole link is one draw call.
//
// Triangle and line counts (documented formulas, checked by the tests):
//   cylinder of N segments : 2N (wall strip) + N + N (two cap fans) = 4N triangles,
//                            3N lines (two rims of N, N wall generators);
//   box / tapered prism    : 12 triangles, 12 lines (24 vertices: flat face normals);
//   sphere of N segments   : R = max(2, N / 2) latitude bands; 2 N (R - 1) triangles (one
//                            per segment in the two polar bands, two elsewhere),
//                            N + 2 R lines (a ring near the equator and two meridians).

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace telear::core {

struct MeshVertex {
  float position[3];
  float normal[3];
  float colour[3];
};
static_assert(sizeof(MeshVertex) == 36, "MeshVertex must be tightly packed for the GPU");

struct Mesh {
  std::vector<MeshVertex> vertices;
  std::vector<std::uint32_t> triangles;  // 3 indices per triangle
  std::vector<std::uint32_t> lines;      // 2 indices per line segment

  std::size_t triangle_count() const { return triangles.size() / 3; }
  std::size_t line_count() const { return lines.size() / 2; }
  bool empty() const { return triangles.empty() && lines.empty(); }

  // Appends a vertex and returns its index.
  std::uint32_t add_vertex(const Eigen::Vector3f& position, const Eigen::Vector3f& normal,
                           const Eigen::Vector3f& colour);
  // Appends `other` (indices shifted).
  void append(const Mesh& other);
  // Expands a triangle strip s0 s1 s2 ... (k indices -> k - 2 triangles, alternate ones
  // flipped so every triangle keeps the strip's winding).
  void append_triangle_strip(const std::vector<std::uint32_t>& strip);
  // Expands a triangle fan c r0 r1 ... (k indices -> k - 2 triangles around c).
  void append_triangle_fan(const std::vector<std::uint32_t>& fan);
  // Applies a rigid transform to every position and normal.
  void transform(const Eigen::Matrix4f& T);
};

// Triangle count of a cylinder of `segments` segments: 4 * segments (see the header comment).
constexpr int cylinder_triangle_count(int segments) {
  return 4 * segments;
}
constexpr int cylinder_line_count(int segments) {
  return 3 * segments;
}
constexpr int kBoxTriangleCount = 12;
constexpr int kBoxLineCount = 12;
// The fewest segments that make a closed cylinder.
constexpr int kMinCylinderSegments = 3;

// A capped cylinder whose axis runs from p0 to p1 (p0 != p1, radius > 0, segments >= 3).
// Its wall has 2 (N + 1) vertices with radial normals; each cap has a centre and N rim
// vertices with the axial normal.
void append_cylinder(Mesh& mesh, const Eigen::Vector3f& p0, const Eigen::Vector3f& p1, float radius,
                     int segments, const Eigen::Vector3f& colour);

// A tapered box ("trapezoid prism"): its axis runs from p0 to p1; the cross-section is a
// rectangle of size0 (width, height) at p0 and size1 at p1. `up` (not parallel to the axis)
// picks the direction the height is measured along; width is along axis x up.
void append_tapered_box(Mesh& mesh, const Eigen::Vector3f& p0, const Eigen::Vector3f& p1,
                        const Eigen::Vector2f& size0, const Eigen::Vector2f& size1,
                        const Eigen::Vector3f& up, const Eigen::Vector3f& colour);

// An axis-aligned box of the given full size, centred at `centre`.
void append_box(Mesh& mesh, const Eigen::Vector3f& centre, const Eigen::Vector3f& size,
                const Eigen::Vector3f& colour);

constexpr int sphere_band_count(int segments) {
  return segments / 2 < 2 ? 2 : segments / 2;
}
constexpr int sphere_triangle_count(int segments) {
  return 2 * segments * (sphere_band_count(segments) - 1);
}
constexpr int sphere_line_count(int segments) {
  return segments + 2 * sphere_band_count(segments);
}

// A UV sphere about `centre` (radius > 0, segments >= 3 around the z axis), smooth normals;
// (R + 1) (N + 1) vertices, the seam and the poles duplicated per column.
void append_sphere(Mesh& mesh, const Eigen::Vector3f& centre, float radius, int segments,
                   const Eigen::Vector3f& colour);

// A flat square on z = 0 of edge `size` centred at the origin, normal +z, in tiles x tiles
// squares alternating two colours (a checkerboard gives the eye a depth cue); lines: the
// tile grid.
void append_checker_floor(Mesh& mesh, float size, int tiles, const Eigen::Vector3f& colour_a,
                          const Eigen::Vector3f& colour_b);

}  // namespace telear::core
