#pragma once
// A synthetic image of an ArUco marker (DICT_4X4_50) whose four outer corners land exactly
// where the test says, for detection and registration-check tests without a GL context.
//
// The marker (6 x 6 cells, a one-cell white quiet zone around it) is drawn large, mapped by the
// homography that takes its outer corners to corners_px (cv::aruco order: top-left, top-right,
// bottom-right, bottom-left as printed) on a grid refined `supersample` times (high-res pixel
// u' = S (u + 0.5) - 0.5, as telear/sim/scene_renderer.hpp), then averaged back over S x S blocks,
// so every pixel holds its area coverage: edges sit where a camera would put them. A homography is
// exactly what a pinhole camera without distortion makes of a planar square.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <opencv2/core.hpp>

namespace telear::test {

struct SyntheticMarkerOptions {
  int id = 0;
  int background = 128;      // grey level around the quiet zone
  int supersample = 8;       // S
  double noise_sigma = 0.0;  // grey levels, Gaussian, from cv::RNG(seed)
  std::uint64_t seed = 1;
};

// A CV_8UC1 image of width x height.
cv::Mat synthetic_marker_image(int width, int height,
                               const std::array<Eigen::Vector2d, 4>& corners_px,
                               const SyntheticMarkerOptions& options = {});

}  // namespace telear::test
