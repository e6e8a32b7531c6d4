#pragma once
// Finding an ArUco marker's four corners in an image to sub-pixel precision.
//
// detect_aruco_marker runs cv::aruco's detector (DICT_4X4_50, no corner refinement of its own)
// and keeps marker `id` when it is found exactly once; then refine_marker_corners moves each
// corner onto the black border's outer edges:
//
// On a marker of ~20 px (cells of ~3 px) cv::aruco's corners are only whole-pixel accurate: its
// contour corners lie on integer pixels, and cornerSubPix's window reaches the inner bit
// corners, so it either drifts onto them (errors of several px) or gives up and keeps the
// integer point. Instead, each side's OUTER edge of the black border (black inside, the white
// quiet zone outside) is located to sub-pixel precision where the grey profile along the side's
// normal crosses the midpoint between the two levels (the anti-aliased edge is a symmetric
// blur of a step, so the half-level crossing is the edge), at points along the middle 70 % of
// the side (away from the corners, where two edges mix); a line is fitted to them by total
// least squares, and neighbouring lines are intersected (three passes). The search along the
// normal stays within half a cell of the current edge, so the inner bit edges (one cell further
// in) and the quiet zone's outer edge do not interfere -- half a cell *across* the side (its
// distance from the marker's centre over half the cells) when that is less than a cell along
// it: a marker seen at a slant is foreshortened across two of its sides, and half a cell along
// them reached the dark beyond the quiet zone and pulled them in (issue 26). The corners are
// returned unchanged when the edges cannot be measured (low contrast, a side under 8 px, near the
// image border, or a corner that would move more than 4 px).
//
// Pixels follow OpenCV (telear/vision/camera_model.hpp): the centre of the top-left pixel is (0,
// 0). Corner order is cv::aruco's: the marker's top-left, top-right, bottom-right, bottom-left as
// printed (clockwise in the image when the marker faces the camera).

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

namespace telear::vision {

struct MarkerDetectionOptions {
  bool refine = true;  // refine_marker_corners after the detector
  int cells = 6;       // cells per side, border included (DICT_4X4: 4 bits + 2 border cells)
};

// The four corners of marker `id` (DICT_4X4_50) in `image`, or empty when it is not found
// exactly once. `image` is 8-bit grey (CV_8UC1), RGB (CV_8UC3, telear's channel order) or RGBA
// (CV_8UC4).
std::vector<Eigen::Vector2d> detect_aruco_marker(const cv::Mat& image, int id,
                                                 const MarkerDetectionOptions& options = {});

// The edge refinement above on a CV_8UC1 image; `initial` holds 4 corners in cv::aruco order.
std::vector<Eigen::Vector2d> refine_marker_corners(const cv::Mat& grey,
                                                   const std::vector<Eigen::Vector2d>& initial,
                                                   int cells = 6);

}  // namespace telear::vision
