#include "gl_test_util.hpp"

#include <algorithm>
#include <cstdlib>

namespace telear::render::test {
namespace {

std::unique_ptr<GlContext>& shared_context() {
  static std::unique_ptr<GlContext> context;
  return context;
}

std::string& creation_error() {
  static std::string error;
  return error;
}

}  // namespace

void GlTest::SetUpTestSuite() {
  if (shared_context() || !creation_error().empty()) return;
  auto context = create_headless_context();
  if (context) {
    shared_context() = std::move(context.value());
  } else {
    creation_error() = context.error().message;
  }
}

void GlTest::SetUp() {
  ASSERT_TRUE(shared_context() != nullptr)
      << "GL tests need a headless OpenGL 3.3 context through EGL (Mesa: libegl1, "
         "libgl1-mesa-dri; see TOOLCHAIN.md). "
      << creation_error();
  ASSERT_TRUE(shared_context()->make_current());
}

GlContext* GlTest::context() {
  return shared_context().get();
}

bool differs(const core::Image& image, int x, int y, const Eigen::Vector3i& background,
             int tolerance) {
  for (int c = 0; c < 3; ++c) {
    if (std::abs(static_cast<int>(image.at(x, y, c)) - background[c]) > tolerance) return true;
  }
  return false;
}

long count_covered(const core::Image& image, const Eigen::Vector3i& background) {
  long n = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) n += differs(image, x, y, background);
  }
  return n;
}

Box covered_box(const core::Image& image, const Eigen::Vector3i& background) {
  Box b{image.width, image.height, -1, -1};
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      if (!differs(image, x, y, background)) continue;
      b.min_x = std::min(b.min_x, x);
      b.max_x = std::max(b.max_x, x);
      b.min_y = std::min(b.min_y, y);
      b.max_y = std::max(b.max_y, y);
    }
  }
  return b;
}

std::pair<int, int> covered_span(const core::Image& image, int y,
                                 const Eigen::Vector3i& background) {
  int lo = image.width, hi = -1;
  for (int x = 0; x < image.width; ++x) {
    if (!differs(image, x, y, background)) continue;
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  if (hi < 0) return {1, 0};
  return {lo, hi};
}

}  // namespace telear::render::test
