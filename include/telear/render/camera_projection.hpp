#pragma once
// The GL projection of a calibrated camera, built from its intrinsics, so that a rendered
// point lands exactly where OpenCV's pixel convention puts it. Pure math, no GL calls.
//
// Conventions (telear/render/view_math.hpp): the view matrix is T_cam_base itself, taking base
// coordinates to the OpenCV camera frame (x right, y down, z forward); the projection takes
// p_cam to GL clip coordinates with w = z_cam, NDC y = +1 at the image's top edge.
//
// OpenCV puts pixel centres at integer coordinates: pixel (i, j) covers [i - 0.5, i + 0.5) x
// [j - 0.5, j + 0.5), the image spans [-0.5, W - 0.5] x [-0.5, H - 0.5], row 0 at the top.
// GL puts the centre of window pixel (i, j) at (i + 0.5, j + 0.5), row 0 at the bottom. So the
// pixel position (u, v) must land at window position
//     x_w = u + 0.5,   y_w = H - 0.5 - v,
// and with x_w = (x_ndc + 1) W / 2 and y_w = (y_ndc + 1) H / 2 this gives
//     x_ndc = 2 (u + 0.5) / W - 1,   y_ndc = 1 - 2 (v + 0.5) / H.
// Substituting the pinhole u = (fx x + s y) / z + cx, v = fy y / z + cy and multiplying by
// w = z:
//
//         | 2 fx / W    2 s / W     2 (cx + 0.5) / W - 1        0           |
//   P  =  |    0       -2 fy / H    1 - 2 (cy + 0.5) / H        0           |
//         |    0          0         (f + n) / (f - n)     -2 f n / (f - n)  |
//         |    0          0                 1                   0           |
//
// (s = K(0,1) = alpha_c fx; depth: z = n -> NDC -1, z = f -> NDC +1). This is exact for the
// pinhole part; lens distortion is not a projective map and is handled by the overlay's
// undistort maps or raw look-up texture (telear/render/overlay.hpp).
//
// A framebuffer that shows only part of the camera's pixel plane -- the raw overlay mode's
// margin around the image, a tile -- is described by the pixel (x0, y0) of the plane that
// its top-left pixel shows: it is the same formula with cx - x0, cy - y0 and its own size.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "telear/vision/camera_model.hpp"

namespace telear::render {

struct PinholeProjection {
  double fx = 0.0, fy = 0.0;  // pixels
  double cx = 0.0, cy = 0.0;  // pixels, OpenCV convention
  double skew = 0.0;          // K(0,1), pixels
  int width = 0;              // framebuffer size, pixels
  int height = 0;
  double near_m = 0.05;  // clip distances along z_cam, 0 < near < far
  double far_m = 50.0;

  // The camera's K and image size (the default clip planes).
  static PinholeProjection from_camera(const vision::CameraModel& camera, double near_m = 0.05,
                                       double far_m = 50.0);
  // The same projection for a width x height framebuffer whose top-left pixel shows pixel
  // (x0, y0) of this one's plane.
  PinholeProjection region(int x0, int y0, int region_width, int region_height) const;
};

// The 4x4 matrix above (double, for the exactness tests; cast<float>() for GL).
Eigen::Matrix4d gl_projection(const PinholeProjection& projection);

// The view matrix: T_cam_base, as a 4x4.
Eigen::Matrix4d gl_view(const Eigen::Isometry3d& T_cam_base);

// GL window coordinates (bottom-left origin, pixel centres at + 0.5) <-> OpenCV pixels of a
// framebuffer of the given height.
Eigen::Vector2d window_from_pixel(const Eigen::Vector2d& uv, int height);
Eigen::Vector2d pixel_from_window(const Eigen::Vector2d& xy_window, int height);

// What GL does to a point: clip = P V p, divide by w, viewport transform, then back to
// OpenCV pixels. The tests compare this with cv::projectPoints.
Eigen::Vector2d pixel_of_point(const PinholeProjection& projection,
                               const Eigen::Isometry3d& T_cam_base, const Eigen::Vector3d& p_base);

// The seed's field-of-view view of the same K: 2 atan(H / (2 fy)) vertically and
// 2 atan(W / (2 fx)) horizontally (radians), exact only for a centred principal point.
double vertical_fov(const PinholeProjection& projection);
double horizontal_fov(const PinholeProjection& projection);

}  // namespace telear::render
