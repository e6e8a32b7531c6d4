#pragma once
// Internal to vision: an edge a lens bends, fitted by the ChArUco corners (charuco_board.cpp)
// and the marker corners (marker_detection.cpp). A lens maps the target's straight edges to
// curves; a straight line fitted through an edge's points is then a chord that passes beside
// the corner at its middle or its end (issue 26 item 1: on the simulated rig's lens, k1 =
// -0.28, 0.01-0.02 px, towards the image centre for a board's corners and away from it for a
// marker's, which placed the target 2.3 m away 0.2-0.3 mm too far or too near). So an edge is
// a parabola about its straight line, d = a + b t + bend t^2 (d across the line along a normal
// oriented by the caller, t along it from a point near the corner), and a corner is where two
// edges' tangents cross.

#include <opencv2/core.hpp>
#include <optional>
#include <vector>

namespace telear::vision {

// The total-least-squares line a x + b y + c = 0 ((a, b) a unit normal) through `points`.
cv::Vec3d fit_edge_line(const std::vector<cv::Point2d>& points);

// The bend of the parabola fitted to `points`, t from `near`, d along the line's normal that
// points towards `towards` (a direction: edges oriented alike compare). nullopt with fewer
// than 6 points.
std::optional<double> edge_bend(const std::vector<cv::Point2d>& points, const cv::Point2d& near,
                                const cv::Point2d& towards);

// The line tangent at t = 0 (`near`) to the parabola of the given bend fitted to `points`
// (only a and b are fitted), as a x + b y + c = 0 with (a, b) a unit normal.
cv::Vec3d edge_tangent(const std::vector<cv::Point2d>& points, const cv::Point2d& near,
                       const cv::Point2d& towards, double bend);

}  // namespace telear::vision
