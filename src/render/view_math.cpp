#include "telear/render/view_math.hpp"

#include <cassert>
#include <cmath>

namespace telear::render {

Eigen::Matrix4f gl_from_cv() {
  return Eigen::Vector4f(1.0f, -1.0f, -1.0f, 1.0f).asDiagonal();
}

Eigen::Matrix4f perspective_cv(float fovy_rad, float aspect, float near_m, float far_m) {
  assert(fovy_rad > 0.0f && aspect > 0.0f && near_m > 0.0f && far_m > near_m &&
         "perspective_cv(): invalid frustum");
  const float f = 1.0f / std::tan(fovy_rad / 2.0f);
  Eigen::Matrix4f P_gl = Eigen::Matrix4f::Zero();
  P_gl(0, 0) = f / aspect;
  P_gl(1, 1) = f;
  P_gl(2, 2) = (far_m + near_m) / (near_m - far_m);
  P_gl(2, 3) = 2.0f * far_m * near_m / (near_m - far_m);
  P_gl(3, 2) = -1.0f;
  return P_gl * gl_from_cv();
}

Eigen::Isometry3f look_at_cv(const Eigen::Vector3f& eye_base, const Eigen::Vector3f& target_base,
                             const Eigen::Vector3f& up_base) {
  const Eigen::Vector3f z = (target_base - eye_base).normalized();  // forward
  const Eigen::Vector3f x = z.cross(up_base).normalized();          // right
  assert(x.allFinite() && "look_at_cv(): up is parallel to the viewing direction");
  const Eigen::Vector3f y = z.cross(x);  // down
  Eigen::Matrix3f R_base_cam;
  R_base_cam << x, y, z;
  Eigen::Isometry3f T_cam_base = Eigen::Isometry3f::Identity();
  T_cam_base.linear() = R_base_cam.transpose();
  T_cam_base.translation() = -(R_base_cam.transpose() * eye_base);
  return T_cam_base;
}

}  // namespace telear::render
