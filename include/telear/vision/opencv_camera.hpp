#pragma once
// A CameraModel in OpenCV's terms: the camera matrix, the distortion vector of its model, and
// projection through OpenCV's own function for that model (cv::projectPoints for plumb_bob and
// rational_polynomial, cv::fisheye::projectPoints for equidistant) -- the independent
// reference the tests compare telear's formulas with, and what calib3d calls take.

#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <vector>

#include "telear/vision/camera_model.hpp"

namespace telear::vision {

// K with fx, fy, cx, cy and the skew fx * alpha_c in (0, 1) (which OpenCV's functions ignore).
cv::Matx33d opencv_camera_matrix(const CameraModel& camera);

// The model's D vector as a 1 x N CV_64F matrix (N = 5, 8 or 4), owning its data.
cv::Mat opencv_distortion(const Distortion& distortion);

// Pixels of points given in the base frame, projected by OpenCV's function for the camera's
// model with the camera's pose.
std::vector<cv::Point2d> opencv_project(const CameraModel& camera,
                                        const std::vector<Eigen::Vector3d>& points_base);

}  // namespace telear::vision
