// The arm on a headless EGL context: per-link matrices, solid vs wire-frame coverage, the
// gripper's silhouette, the triangle count the GPU draws, the ghost's transparency.

#include "telear/render/arm_renderer.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <numbers>

#include "gl_test_util.hpp"
#include "telear/core/robot_loader.hpp"
#include "telear/render/offscreen_target.hpp"
#include "telear/render/view_math.hpp"
#include "test_util/test_util.hpp"

namespace telear::render {
namespace {

using test::GlTest;

using test::kBlack;
constexpr int kW = 320, kH = 240;
constexpr float kFovy = std::numbers::pi_v<float> / 4;  // 45 degrees

class ArmRendererTest : public GlTest {
 protected:
  void SetUp() override {
    GlTest::SetUp();
    if (HasFatalFailure()) return;
    model = telear::test::puma560();
    ASSERT_TRUE(model);
    auto d = core::body_description_for(*model);
    ASSERT_TRUE(d) << d.error().message;
    description = *d;
    auto t = OffscreenTarget::create(kW, kH);
    ASSERT_TRUE(t) << t.error().message;
    target = std::move(t.value());
    projection = perspective_cv(kFovy, float(kW) / kH, 0.05f, 20.0f);
    // The whole arm, from the front-right, slightly above.
    T_cam_base = look_at_cv({2.2f, -1.6f, 1.4f}, {0.2f, 0, 0.6f}).matrix();
  }

  core::Image render(ArmRenderer& arm, const DrawOptions& options = {}) {
    target.clear();
    arm.draw(projection, T_cam_base, options);
    return target.read_rgb();
  }

  core::RobotModelPtr model;
  core::BodyDescription description;
  OffscreenTarget target;
  Eigen::Matrix4f projection;
  Eigen::Matrix4f T_cam_base;
};

TEST_F(ArmRendererTest, MovingJointFiveUploadsTheMatricesOfLinksFiveAndSixOnly) {
  const core::ArmBody body = core::build_arm_body(description);
  core::ArmBodyPose pose(*model, body);
  auto arm = ArmRenderer::create(body);
  ASSERT_TRUE(arm) << arm.error().message;
  EXPECT_EQ(arm->update(pose).count, 9);   // the first upload: every part
  EXPECT_TRUE(arm->update(pose).empty());  // nothing moved: nothing uploaded
  const long uploaded = arm->matrices_uploaded();

  pose.set_joint(4, 0.6);  // joint 5
  const core::PartRange r = arm->update(pose);
  EXPECT_EQ(r.first, 5);  // link 5 ...
  EXPECT_EQ(r.end(), 9);  // ... link 6 and the two fingers on link 6
  EXPECT_EQ(arm->matrices_uploaded() - uploaded, 4);
  for (int k = 0; k < 5; ++k) EXPECT_FALSE(r.contains(k)) << "link " << k << " was uploaded";

  // What was uploaded is what is drawn: the picture matches a fresh renderer at that pose.
  auto fresh = ArmRenderer::create(body);
  ASSERT_TRUE(fresh);
  core::ArmBodyPose pose2(*model, body);
  pose2.set_configuration(pose.q());
  fresh->update(pose2);
  EXPECT_EQ(render(*arm).pixels, render(*fresh).pixels);
}

TEST_F(ArmRendererTest, TheGpuDrawsTheFormulasTriangleCount) {
  int cylinders = 0;
  for (const auto& link : description.links) {
    for (const core::ShapeSpec& s : link) cylinders += s.kind == core::ShapeSpec::Kind::kCylinder;
  }
  GLuint query = 0;
  glGenQueries(1, &query);
  std::vector<long> drawn;
  for (int segments : {8, 50}) {
    const core::ArmBody body = core::build_arm_body(description, {.segments_override = segments});
    core::ArmBodyPose pose(*model, body);
    auto arm = ArmRenderer::create(body);
    ASSERT_TRUE(arm);
    arm->update(pose);
    EXPECT_EQ(arm->triangle_count(), body.triangle_count());
    target.clear();
    glBeginQuery(GL_PRIMITIVES_GENERATED, query);
    arm->draw(projection, T_cam_base);
    glEndQuery(GL_PRIMITIVES_GENERATED);
    GLuint primitives = 0;
    glGetQueryObjectuiv(query, GL_QUERY_RESULT, &primitives);
    EXPECT_EQ(primitives, body.triangle_count()) << segments << " segments";
    drawn.push_back(primitives);
  }
  glDeleteQueries(1, &query);
  EXPECT_EQ(drawn[1] - drawn[0],
            cylinders * (core::cylinder_triangle_count(50) - core::cylinder_triangle_count(8)));
}

TEST_F(ArmRendererTest, WireframeCoversLessThanSolidAndLiesInsideIt) {
  const core::ArmBody body = core::build_arm_body(description, {.segments_override = 8});
  core::ArmBodyPose pose(*model, body);
  pose.set_configuration(*model->named_configuration("qn"));
  auto arm = ArmRenderer::create(body);
  ASSERT_TRUE(arm);
  arm->update(pose);
  // Closer than the default view, so that the arm fills a good part of the image.
  T_cam_base = look_at_cv({1.2f, -0.9f, 1.0f}, {0.25f, 0, 0.6f}).matrix();
  const core::Image solid = render(*arm);
  DrawOptions wire;
  wire.style = DrawOptions::Style::kWireframe;
  const core::Image lines = render(*arm, wire);
  const long solid_px = test::count_covered(solid, kBlack);
  const long line_px = test::count_covered(lines, kBlack);
  EXPECT_GT(solid_px, kW * kH / 10);  // the arm is in view
  EXPECT_GT(line_px, solid_px / 20);
  EXPECT_LT(line_px, solid_px / 2);
  std::printf("solid %ld px, wire-frame %ld px\n", solid_px, line_px);
  // Lines are edges of the solid: (almost) every line pixel lies on the solid's silhouette,
  // allowing one pixel for rasterisation rules at the border.
  long outside = 0;
  for (int y = 1; y < kH - 1; ++y) {
    for (int x = 1; x < kW - 1; ++x) {
      if (!test::differs(lines, x, y, kBlack)) continue;
      bool near_solid = false;
      for (int dy = -1; dy <= 1 && !near_solid; ++dy) {
        for (int dx = -1; dx <= 1 && !near_solid; ++dx) {
          near_solid = test::differs(solid, x + dx, y + dy, kBlack);
        }
      }
      outside += !near_solid;
    }
  }
  EXPECT_LE(outside, line_px / 100);
  // The solid is lit: its pixels are not one flat colour.
  const test::Box box = test::covered_box(solid, kBlack);
  EXPECT_FALSE(box.empty());
}

TEST_F(ArmRendererTest, GripperOpeningChangesTheSilhouetteWidth) {
  const core::ArmBody body = core::build_arm_body(description);
  core::ArmBodyPose pose(*model, body);
  pose.set_configuration(*model->named_configuration("qr"));  // arm straight up
  const Eigen::Isometry3d T_base_6 = pose.kinematics().T_base_link[6];
  ASSERT_GT(T_base_6.linear().col(2).z(), 0.999);  // the tool points up
  auto arm = ArmRenderer::create(body);
  ASSERT_TRUE(arm);
  // Look at the fingers horizontally along x6, image up = the tool direction, so the
  // opening axis y6 is horizontal in the image and nothing else is above the palm.
  const core::GripperSpec& g = *body.gripper;
  const Eigen::Vector3f centre = (T_base_6.cast<float>() * g.centre);
  const float distance = 0.4f;
  const Eigen::Vector3f eye = centre + distance * T_base_6.linear().col(0).cast<float>();
  T_cam_base = look_at_cv(eye, centre, Eigen::Vector3f::UnitZ()).matrix();
  const float f_px = (kH / 2.0f) / std::tan(kFovy / 2);
  const int row = kH / 2;  // the fingers' centre row

  std::vector<int> widths;
  for (float opening : {0.0f, 0.02f, 0.08f}) {
    pose.set_gripper_opening(opening);
    arm->update(pose);
    const core::Image img = render(*arm);
    const auto [lo, hi] = test::covered_span(img, row, kBlack);
    ASSERT_LE(lo, hi) << "no gripper at row " << row;
    widths.push_back(hi - lo + 1);
    // Outer width = opening + two finger thicknesses, seen from the fingers' front faces.
    const float extent = opening + 2 * g.finger_size.y();
    const float expected = f_px * extent / (distance - g.finger_size.x() / 2);
    EXPECT_NEAR(widths.back(), expected, 3.0f) << "opening " << opening;
    // Open: the gap between the fingers is background; closed: no gap.
    EXPECT_EQ(test::differs(img, kW / 2, row, kBlack), opening == 0.0f) << opening;
  }
  EXPECT_LT(widths[0], widths[1]);
  EXPECT_LT(widths[1], widths[2]);
}

TEST_F(ArmRendererTest, GhostBlendsItsNearestSurfaceOverTheBackground) {
  const core::ArmBody body = core::build_arm_body(description);
  core::ArmBodyPose pose(*model, body);
  auto arm = ArmRenderer::create(body);
  ASSERT_TRUE(arm);
  arm->update(pose);
  DrawOptions opaque;
  opaque.colour = Eigen::Vector3f(0.2f, 0.9f, 0.3f);
  opaque.lighting.ambient = Eigen::Vector3f::Ones();  // flat colour: exact arithmetic
  opaque.lighting.diffuse = Eigen::Vector3f::Zero();
  DrawOptions ghost = opaque;
  ghost.alpha = 0.5f;
  auto draw = [&](const DrawOptions& o) {
    target.clear(0.0f, 0.0f, 1.0f, 1.0f);  // blue background
    arm->draw(projection, T_cam_base, o);
    return target.read_rgb();
  };
  const core::Image a = draw(opaque);
  const core::Image b = draw(ghost);
  const Eigen::Vector3i blue(0, 0, 255);
  const long covered = test::count_covered(a, blue);
  ASSERT_GT(covered, 1000);
  EXPECT_EQ(test::count_covered(b, blue), covered);  // same silhouette
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      if (!test::differs(a, x, y, blue)) continue;
      // Exactly one layer blended: 0.5 colour + 0.5 background, wherever the arm overlaps
      // itself (a second layer would give 0.75 / 0.25).
      for (int c = 0; c < 3; ++c) {
        const int expected = (a.at(x, y, c) + (c == 2 ? 255 : 0) + 1) / 2;
        ASSERT_NEAR(b.at(x, y, c), expected, 2) << x << "," << y << " channel " << c;
      }
    }
  }
}

TEST_F(ArmRendererTest, ADefaultBodyRendersForARobotWithoutABodyFile) {
  auto urdf = core::load_robot(telear::test::data_path("robots/puma560.urdf"));
  ASSERT_TRUE(urdf);
  const core::ArmBody body = core::build_arm_body(core::default_body_description(**urdf));
  core::ArmBodyPose pose(**urdf, body);
  auto arm = ArmRenderer::create(body);
  ASSERT_TRUE(arm);
  arm->update(pose);
  EXPECT_GT(test::count_covered(render(*arm), kBlack), kW * kH / 200);
}

}  // namespace
}  // namespace telear::render
