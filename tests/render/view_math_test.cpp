// Camera conventions of render/ (view_math.hpp) and GL wrappers without a context.

#include "telear/render/view_math.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "telear/core/image.hpp"
#include "telear/render/gl_objects.hpp"
#include "telear/render/offscreen_target.hpp"

namespace telear::render {
namespace {

Eigen::Vector3f ndc(const Eigen::Matrix4f& P, const Eigen::Vector3f& p_cam) {
  const Eigen::Vector4f clip = P * p_cam.homogeneous();
  return clip.head<3>() / clip.w();
}

TEST(ViewMathTest, PerspectiveFollowsTheOpenCvCameraFrame) {
  const float fovy = std::numbers::pi_v<float> / 3;
  const Eigen::Matrix4f P = perspective_cv(fovy, 4.0f / 3.0f, 0.1f, 10.0f);
  EXPECT_TRUE(ndc(P, {0, 0, 2}).head<2>().isZero(1e-6f));  // optical axis: image centre
  EXPECT_GT(ndc(P, {0, -0.5f, 2}).y(), 0.0f);              // y_cam < 0 (up in the image): NDC y > 0
  EXPECT_GT(ndc(P, {0.5f, 0, 2}).x(), 0.0f);               // x_cam > 0: right
  EXPECT_NEAR(ndc(P, {0, 0, 0.1f}).z(), -1.0f, 1e-5f);     // near plane
  EXPECT_NEAR(ndc(P, {0, 0, 10.0f}).z(), 1.0f, 1e-4f);     // far plane
  // The top edge of the field of view lands on NDC y = +1.
  const float t = std::tan(fovy / 2);
  EXPECT_NEAR(ndc(P, {0, -2 * t, 2}).y(), 1.0f, 1e-5f);
}

TEST(ViewMathTest, LookAtPutsTheTargetAheadAndUpAtTheTop) {
  const Eigen::Vector3f eye(2, 1, 1.5f), target(0, 0, 0.5f);
  const Eigen::Isometry3f T_cam_base = look_at_cv(eye, target, Eigen::Vector3f::UnitZ());
  const Eigen::Vector3f p = T_cam_base * target;
  EXPECT_TRUE(p.head<2>().isZero(1e-5f));
  EXPECT_NEAR(p.z(), (target - eye).norm(), 1e-5f);
  EXPECT_TRUE((T_cam_base * eye).isZero(1e-5f));
  // A point above the target is above the image centre: y_cam < 0.
  EXPECT_LT((T_cam_base * (target + Eigen::Vector3f(0, 0, 0.3f))).y(), 0.0f);
  EXPECT_NEAR(T_cam_base.linear().determinant(), 1.0f, 1e-5f);
}

TEST(ViewMathTest, GlFromCvIsAProperRotation) {
  EXPECT_FLOAT_EQ((gl_from_cv().topLeftCorner<3, 3>().determinant()), 1.0f);
}

TEST(GlObjectsTest, WrappersAreBuiltAndMovedWithoutAContext) {
  // No GL call happens here (epoxy would abort without a context).
  Buffer a;
  Buffer b = std::move(a);
  EXPECT_FALSE(b);
  Program p;
  EXPECT_EQ(p.id(), 0u);
  OffscreenTarget t;
  EXPECT_EQ(t.width(), 0);
  static_assert(!std::is_copy_constructible_v<Texture>);
  static_assert(std::is_nothrow_move_constructible_v<Framebuffer>);
}

TEST(ImageTest, RowsAreTopFirstAndTightlyPacked) {
  core::Image img(4, 3, 3);
  EXPECT_EQ(img.pixels.size(), 36u);
  img.at(1, 2, 0) = 7;
  EXPECT_EQ(img.pixels[2 * 12 + 3], 7);
}

}  // namespace
}  // namespace telear::render
