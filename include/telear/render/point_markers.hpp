#pragma once
// Round markers drawn at 3-D points (joint origins, waypoints, observed tool positions),
// a fixed size in pixels whatever their distance.
//
// Each point is one GL point sprite; its fragment shader paints a smooth radial profile
// around the EXACT window position of the projected point (computed in the vertex shader
// from the clip coordinates and the viewport, not snapped to pixels):
//     weight(d) = (1 - (d / radius)^2)^2  for d < radius,  0 beyond,
// d = distance from the fragment centre to the projected point. The profile is symmetric
// and smooth, so the weight-centroid of the rendered pixels is the projected point to a few
// thousandths of a pixel: the overlay tests locate markers this way.
//
// Output is premultiplied (rgb = colour * weight, alpha = weight), blended with
// (ONE, ONE_MINUS_SRC_ALPHA) over the framebuffer; no depth test (markers stay visible).
// Conventions of projection / T_view_base: telear/render/view_math.hpp.

#include <Eigen/Core>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/render/gl_objects.hpp"

namespace telear::render {

class PointMarkers {
 public:
  PointMarkers() = default;
  // Needs a current context.
  static Result<PointMarkers> create();

  // Draws one marker per point (base frame, metres) into the bound framebuffer / viewport.
  // radius_px in (0, 100].
  void draw(const Eigen::Matrix4f& projection, const Eigen::Matrix4f& T_view_base,
            const std::vector<Eigen::Vector3f>& points_base, float radius_px,
            const Eigen::Vector3f& colour) const;

 private:
  Program program_;
  VertexArray vao_;
  Buffer points_;
  GLint u_projection_ = -1, u_T_view_base_ = -1, u_viewport_ = -1, u_radius_ = -1, u_colour_ = -1;
};

}  // namespace telear::render
