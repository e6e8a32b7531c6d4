#pragma once
// Internal to vision: what the edge fits of the marker detector (marker_detection.cpp) and
// of the ChArUco corners (charuco_board.cpp) both read from a grey image, defined once (their
// levels are medians: vision::median_of, mono_calibration.hpp).

#include <cmath>
#include <cstdint>
#include <opencv2/core.hpp>

namespace telear::vision {

// Bilinear grey level of a CV_8UC1 image at (x, y), pixel centres at integers; the caller
// keeps the point at least one pixel inside the image.
inline double bilinear_grey(const cv::Mat& grey, double x, double y) {
  const int x0 = static_cast<int>(std::floor(x));
  const int y0 = static_cast<int>(std::floor(y));
  const double fx = x - x0, fy = y - y0;
  const auto at = [&grey](int u, int v) {
    return static_cast<double>(grey.at<std::uint8_t>(v, u));
  };
  return (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) +
         fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1));
}

}  // namespace telear::vision
