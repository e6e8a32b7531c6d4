#pragma once
// OpenCV's pose form (a Rodrigues rotation vector rvec and a translation tvec, as returned by
// solvePnP, calibrateCamera and stereoCalibrate) as telear's Eigen::Isometry3d:
// T maps points of the object frame into the camera frame, p_cam = R p_obj + t.

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

namespace telear::vision {

// rvec: 3x1 or 1x3 CV_64F rotation vector; tvec: 3 CV_64F values.
Eigen::Isometry3d pose_from_rvec_tvec(const cv::Mat& rvec, const cv::Mat& tvec);

}  // namespace telear::vision
