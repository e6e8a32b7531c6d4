#pragma once
// Test images of calibration patterns with exactly known point positions: the target plane
// (metres) is mapped to pixels by a homography and every pixel is the average of 8x8
// samples of the ideal black-and-white target, so edges are anti-aliased like a camera's.

#include <opencv2/core.hpp>

#include "telear/vision/calibration_pattern.hpp"

namespace telear::test {

// 8-bit grey image of `pattern` (with a one-square white margin) seen through
// `H_pixel_target` (3x3, target metres -> pixels) on a mid-grey background.
cv::Mat render_pattern(const vision::CalibrationPattern& pattern, const cv::Matx33d& H_pixel_target,
                       cv::Size size);

// Where H puts the pattern's object points.
std::vector<cv::Point2d> true_image_points(const vision::CalibrationPattern& pattern,
                                           const cv::Matx33d& H_pixel_target);

// A homography that shows the pattern centred, about `width_px` wide, seen from a tilt of
// `tilt_deg` about the vertical axis (perspective).
cv::Matx33d view_homography(const vision::CalibrationPattern& pattern, cv::Size size,
                            double width_px, double tilt_deg, double roll_deg = 0.0);

}  // namespace telear::test
