#pragma once
// GLSL 3.30 core sources of render/'s programs, kept as C++ strings so that the binaries need
// no shader files at run time.
//
// surface (MeshSetRenderer): per part k, with the part matrices in a std140 uniform block
//   "Parts" (mat4 T_base_part[kMaxParts], binding point kPartsBinding):
//     gl_Position = u_projection * u_T_view_base * T_base_part[k] * position
//   lit (solid): per-vertex (Gouraud) lighting, as the seed's Direct3D fixed-function set-up:
//     rgb = colour * (u_ambient + u_diffuse * max(dot(n, l), 0)), n turned towards the
//     viewer, l = u_light_dir_view (unit, towards the light);
//   unlit (wire-frame lines): rgb = colour; alpha = u_alpha in both.
//   Per-vertex rather than per-fragment: on llvmpipe the fragment stage dominates, and the
//   seed lit per vertex too.
// background (VideoBackground, when it cannot blit): a textured quad over the viewport.

namespace telear::render::shaders {

constexpr int kPartsBinding = 0;

extern const char* const kSurfaceVertex;
extern const char* const kSurfaceFragment;
extern const char* const kBackgroundVertex;
extern const char* const kBackgroundFragment;

}  // namespace telear::render::shaders
