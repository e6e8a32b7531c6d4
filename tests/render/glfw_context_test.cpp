// The GLFW window context. It needs a display: under CI's headless run it is skipped (the
// EGL tests cover the renderer); run it with `xvfb-run -a ctest -R render_glfw`.

#include "telear/render/glfw_context.hpp"

#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include <cstdlib>
#include <vector>

namespace telear::render {
namespace {

bool have_display() {
  return std::getenv("DISPLAY") != nullptr || std::getenv("WAYLAND_DISPLAY") != nullptr;
}

TEST(GlfwContextTest, AWindowHasAGl33CoreContextAndDraws) {
  if (!have_display()) GTEST_SKIP() << "no display (DISPLAY / WAYLAND_DISPLAY unset)";
  GlfwOptions options;
  options.width = 64;
  options.height = 48;
  options.visible = false;
  auto context = GlfwContext::create(options);
  ASSERT_TRUE(context) << context.error().message;
  ASSERT_TRUE((*context)->make_current());
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  EXPECT_GE(major * 10 + minor, 33);
  int w = 0, h = 0;
  (*context)->framebuffer_size(w, h);
  ASSERT_GT(w, 0);
  ASSERT_GT(h, 0);
  glViewport(0, 0, w, h);
  glClearColor(0.0f, 1.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  std::vector<unsigned char> pixel(4);
  glReadPixels(w / 2, h / 2, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, pixel.data());
  EXPECT_EQ(pixel[1], 255);
  EXPECT_EQ(pixel[0], 0);
  (*context)->swap_buffers();
  EXPECT_FALSE((*context)->should_close());
}

TEST(GlfwContextTest, AStereoRequestFallsBackCleanlyWhenTheDriverHasNone) {
  if (!have_display()) GTEST_SKIP() << "no display (DISPLAY / WAYLAND_DISPLAY unset)";
  GlfwOptions options;
  options.width = 32;
  options.height = 32;
  options.visible = false;
  options.request_stereo = true;
  auto context = GlfwContext::create(options);
  ASSERT_TRUE(context) << context.error().message;
  EXPECT_TRUE((*context)->stereo_requested());
  GLboolean stereo = GL_FALSE;
  glGetBooleanv(GL_STEREO, &stereo);
  EXPECT_EQ((*context)->stereo_granted(), stereo == GL_TRUE);
}

}  // namespace
}  // namespace telear::render
