#pragma once
// A rectified stereo pair as ROS camera_info states it, and the pose of the right camera
// relative to the left recovered from it.
//
// Each camera's file carries R (rectification_matrix: raw camera frame -> rectified frame)
// and P (projection_matrix, 3x4). The rectified frames are parallel; P projects points given
// in the left camera's rectified frame:
//
//   P = [fx' s' cx' Tx; 0 fy' cy' Ty; 0 0 1 0]      left: Tx = Ty = 0
//   right (horizontal pair): Tx = -fx' B, Ty = 0    B: the baseline, metres
//
// so P = K' [I | t] with t = K'^-1 (Tx, Ty, 0) = (-B, 0, 0), and a point goes from the left
// camera to the right camera by
//
//   p_right = R2^T (R1 p_left + t),   i.e.  R_right_left = R2^T R1,  t_right_left = R2^T t.
//
// (A vertical pair, Tx = 0 and Ty = -fy' B, follows from the same t.) This is
// cv::stereoRectify's convention, and ROS's camera_calibration writes R1, P1 to the left
// file and R2, P2 to the right one.

#include <Eigen/Geometry>

#include "telear/core/result.hpp"

namespace telear::vision {

using Matrix34d = Eigen::Matrix<double, 3, 4>;

struct Rectification {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();  // camera -> rectified frame (a rotation)
  Matrix34d P = Matrix34d::Zero();                  // rectified projection, last row 0 0 1 0

  // The pixel offset (Tx, Ty) of the rectified projection, P(0,3) and P(1,3).
  double tx() const { return P(0, 3); }
  double ty() const { return P(1, 3); }
};

// The pose of the right camera in the left camera's frame as a transform p_right = T p_left
// (R = R2^T R1, t = R2^T K'^-1 (Tx, Ty, 0)). Errors, prefixed "left: " or "right: " and
// naming projection_matrix: the left camera's Tx or Ty is not 0 (the files may be swapped),
// the right one's are both 0 (no baseline), the two disagree in fx' or fy' (not one
// rectified pair).
Result<Eigen::Isometry3d> right_from_left_rectified(const Rectification& left,
                                                    const Rectification& right);

}  // namespace telear::vision
