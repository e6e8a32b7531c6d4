#pragma once
// Conversions between OpenCV's frames (cv::Mat, BGR for video and cameras) and core::Image
// (RGB8, top row first, tightly packed), and scaling, for the vision sources and pipeline.

#include "telear/core/image.hpp"

namespace cv {
class Mat;
}

namespace telear::vision {

// An 8-bit BGR (3 channels) or grey (1 channel) frame -> RGB8, scaled to width x height when
// both are > 0 and differ from the frame's size (INTER_AREA: the right filter to shrink).
// An empty or other-typed frame gives an empty image.
core::Image rgb_from_bgr(const cv::Mat& frame, int width = 0, int height = 0);

// An RGB8 image scaled to width x height (INTER_AREA shrinking, INTER_LINEAR enlarging).
core::Image resize_rgb(const core::Image& image, int width, int height);

}  // namespace telear::vision
