#pragma once
// The camera conventions every draw call in render/ follows.
//
//   T_view_base (= T_cam_base): camera-from-base, a rigid transform into the OpenCV camera
//     frame: x right, y DOWN, z FORWARD (into the scene), metres. p_cam = T_cam_base p_base.
//   projection: a 4x4 matrix taking homogeneous p_cam (OpenCV frame) to GL clip coordinates,
//     such that after the divide by w (= z_cam, > 0 in front of the camera):
//       NDC x = -1 at the image's left edge, +1 at its right edge,
//       NDC y = +1 at the image's TOP edge (image row 0), -1 at its bottom edge,
//       NDC z = -1 at the near plane, +1 at the far plane (GL's default depth range).
//     So the framebuffer holds the image upright in GL's bottom-up row order: GL row
//     (height - 1 - v) is image row v. OffscreenTarget::read_rgb() flips the rows back, so
//     its row 0 is the image's top row.
//   An exact projection from the intrinsics K (fx, fy, cx, cy, skew; OpenCV's pixel
//   convention) is built in telear/render/camera_projection.hpp. The helpers below are the
//   symmetric-frustum special case, for tests, benchmarks and default views.
//
// A GL-style projection P_gl (eye looking down -z, y up) is turned into this convention by
// P_gl * gl_from_cv(): gl_from_cv() = diag(1, -1, -1, 1), a 180 degree turn about x (det +1,
// so triangle winding is unchanged).

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace telear::render {

Eigen::Matrix4f gl_from_cv();

// Symmetric perspective in the convention above: vertical field of view fovy (rad), aspect
// = width / height, 0 < near < far (m). The principal point is the image centre.
Eigen::Matrix4f perspective_cv(float fovy_rad, float aspect, float near_m, float far_m);

// T_cam_base of a camera at `eye` looking at `target` (base frame), image "up" (-y_cam) as
// close to `up` as possible. eye != target, up not parallel to the viewing direction.
Eigen::Isometry3f look_at_cv(const Eigen::Vector3f& eye_base, const Eigen::Vector3f& target_base,
                             const Eigen::Vector3f& up_base = Eigen::Vector3f::UnitZ());

}  // namespace telear::render
