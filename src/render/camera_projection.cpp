#include "telear/render/camera_projection.hpp"

#include <cassert>
#include <cmath>

namespace telear::render {

PinholeProjection PinholeProjection::from_camera(const vision::CameraModel& camera, double near_m,
                                                 double far_m) {
  PinholeProjection p;
  p.fx = camera.fx;
  p.fy = camera.fy;
  p.cx = camera.cx;
  p.cy = camera.cy;
  p.skew = camera.skew();
  p.width = camera.width;
  p.height = camera.height;
  p.near_m = near_m;
  p.far_m = far_m;
  return p;
}

PinholeProjection PinholeProjection::region(int x0, int y0, int region_width,
                                            int region_height) const {
  PinholeProjection p = *this;
  p.cx = cx - x0;
  p.cy = cy - y0;
  p.width = region_width;
  p.height = region_height;
  return p;
}

Eigen::Matrix4d gl_projection(const PinholeProjection& c) {
  assert(c.width > 0 && c.height > 0 && c.fx > 0.0 && c.fy > 0.0);
  assert(c.near_m > 0.0 && c.far_m > c.near_m);
  const double W = c.width, H = c.height, n = c.near_m, f = c.far_m;
  Eigen::Matrix4d P = Eigen::Matrix4d::Zero();
  P(0, 0) = 2.0 * c.fx / W;
  P(0, 1) = 2.0 * c.skew / W;
  P(0, 2) = 2.0 * (c.cx + 0.5) / W - 1.0;
  P(1, 1) = -2.0 * c.fy / H;
  P(1, 2) = 1.0 - 2.0 * (c.cy + 0.5) / H;
  P(2, 2) = (f + n) / (f - n);
  P(2, 3) = -2.0 * f * n / (f - n);
  P(3, 2) = 1.0;
  return P;
}

Eigen::Matrix4d gl_view(const Eigen::Isometry3d& T_cam_base) {
  return T_cam_base.matrix();
}

Eigen::Vector2d window_from_pixel(const Eigen::Vector2d& uv, int height) {
  return {uv.x() + 0.5, height - 0.5 - uv.y()};
}

Eigen::Vector2d pixel_from_window(const Eigen::Vector2d& xy_window, int height) {
  return {xy_window.x() - 0.5, height - 0.5 - xy_window.y()};
}

Eigen::Vector2d pixel_of_point(const PinholeProjection& projection,
                               const Eigen::Isometry3d& T_cam_base, const Eigen::Vector3d& p_base) {
  const Eigen::Vector4d clip =
      gl_projection(projection) * gl_view(T_cam_base) * p_base.homogeneous();
  const Eigen::Vector2d ndc = clip.head<2>() / clip.w();
  const Eigen::Vector2d window((ndc.x() + 1.0) * 0.5 * projection.width,
                               (ndc.y() + 1.0) * 0.5 * projection.height);
  return pixel_from_window(window, projection.height);
}

double vertical_fov(const PinholeProjection& p) {
  return 2.0 * std::atan(p.height / (2.0 * p.fy));
}

double horizontal_fov(const PinholeProjection& p) {
  return 2.0 * std::atan(p.width / (2.0 * p.fx));
}

}  // namespace telear::render
