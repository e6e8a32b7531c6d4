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
// ycbcr (VideoBackground::upload_planes): a decoded JPEG's planes to RGB on the GPU, JFIF's
//   full-range BT.601: R = Y + 1.402 Cr', G = Y - 0.344136 Cb' - 0.714136 Cr', B = Y + 1.772 Cb'
//   (Cb' = Cb - 128 ...); the chroma planes sampled bilinearly at the pixel's centre; rows
//   flipped (the planes are top row first, the target bottom-up).

namespace telear::render::shaders {

constexpr int kPartsBinding = 0;

extern const char* const kSurfaceVertex;
extern const char* const kSurfaceFragment;
extern const char* const kBackgroundVertex;
extern const char* const kBackgroundFragment;
extern const char* const kYCbCrFragment;

}  // namespace telear::render::shaders
