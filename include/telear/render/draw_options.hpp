#pragma once
// How a set of meshes is drawn: solid (lit) or wire-frame, opaque or ghost (alpha), and the
// scene lighting of the seed's set-up: one ambient term plus one directional light.
//
// Solid shading per vertex, as the seed's fixed-function set-up (view-space normal n, unit
// direction towards the light l, vertex or override colour c):
//   rgb = c * (ambient + diffuse * max(dot(n, l), 0)),   alpha = options.alpha
// Back faces are lit with the flipped normal (open shapes look right from inside too).
// Wire-frame draws the meshes' line lists, unlit, in the vertex (or override) colour.
//
// Ghost (alpha < 1): a depth-only pass first, then colour with blending where depth is
// equal, so only the ghost's nearest surface is blended over what is behind it (no see-
// through internal faces). The ghost writes depth, so it also hides what is drawn later.

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace telear::render {

struct Lighting {
  // Unit direction TOWARDS the light, in the base frame (above, in front, to one side).
  Eigen::Vector3f direction_base = Eigen::Vector3f(0.4f, -0.3f, 1.0f).normalized();
  Eigen::Vector3f ambient{0.35f, 0.35f, 0.35f};
  Eigen::Vector3f diffuse{0.75f, 0.75f, 0.75f};
};

struct DrawOptions {
  enum class Style { kSolid, kWireframe };
  Style style = Style::kSolid;
  float alpha = 1.0f;                     // 1: opaque; < 1: ghost
  std::optional<Eigen::Vector3f> colour;  // replaces the vertex colours (e.g. a ghost tint)
  // Parts (indices into the set) drawn in highlight_colour instead, lit and blended like the
  // rest: the operator's eye goes to them (the ghost's links in contact with an obstacle).
  std::vector<int> highlight_parts;
  Eigen::Vector3f highlight_colour{0.95f, 0.08f, 0.08f};
  Lighting lighting;
  // Skip triangles facing away from the camera (counter-clockwise = front, with a projection
  // following view_math.hpp). The body's meshes are closed and wound outwards, so this only
  // saves work (half the triangles, a third of the time on llvmpipe); turn it off for open
  // meshes seen from behind (the floor from below).
  bool cull_back_faces = true;
};

}  // namespace telear::render
