#pragma once
// Shared set-up of the GL tests: one headless EGL context per test process (llvmpipe in CI,
// no X server). When no EGL display can be created the tests FAIL with the reason: a CI
// machine without Mesa's EGL must not pass the GL tests by skipping them.

#include <gtest/gtest.h>

#include <Eigen/Core>

#include <memory>
#include <string>
#include <utility>

#include "telear/core/image.hpp"
#include "telear/render/egl_context.hpp"

namespace telear::render::test {

class GlTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite();
  void SetUp() override;
  static GlContext* context();
};

// Pixels whose RGB differs from `background` by more than `tolerance` in any channel.
bool differs(const core::Image& image, int x, int y, const Eigen::Vector3i& background,
             int tolerance = 8);
// The background colour of the renderer tests' clears.
inline const Eigen::Vector3i kBlack(0, 0, 0);

long count_covered(const core::Image& image, const Eigen::Vector3i& background);

// Bounding box of the covered pixels: {min_x, min_y, max_x, max_y}; min > max when none.
struct Box {
  int min_x, min_y, max_x, max_y;
  bool empty() const { return min_x > max_x; }
};
Box covered_box(const core::Image& image, const Eigen::Vector3i& background);

// Leftmost and rightmost covered columns in row y ({1, 0} when none).
std::pair<int, int> covered_span(const core::Image& image, int y,
                                 const Eigen::Vector3i& background);

}  // namespace telear::render::test
