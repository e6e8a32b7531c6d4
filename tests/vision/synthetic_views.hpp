#pragma once
// Synthetic calibration data with a known truth: a stereo rig of two distorted pinhole
// cameras, random poses of a pattern that keep it fully inside both images, and the
// pattern's image points from cv::projectPoints plus Gaussian pixel noise (fixed seeds).
// Calibration runs on these corner lists directly; rendered images come on top later.

#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <random>
#include <vector>

#include "telear/vision/calibration_pattern.hpp"
#include "telear/vision/camera_model.hpp"
#include "telear/vision/stereo_calibration.hpp"

namespace telear::test {

struct SyntheticRig {
  vision::CameraModel left;
  vision::CameraModel right;
  Eigen::Isometry3d T_right_left;  // X_R = T_right_left * X_L (OpenCV's R, T)
};

// 640x480, fx ~ 800, principal points near the centre, k1 = -0.3, k2 = 0.1, small p1, p2;
// the right camera 6 cm to the right of the left one, turned by about 1 degree.
SyntheticRig default_rig();

// `count` poses of the pattern in the left camera (T_left_target): centre 0.35 .. 0.65 m
// away and in the middle 60 % of the image, tilted 30 .. 50 degrees about a random axis,
// with every point at least `margin_px` inside both images.
std::vector<Eigen::Isometry3d> random_pattern_poses(const SyntheticRig& rig,
                                                    const vision::CalibrationPattern& pattern,
                                                    int count, std::mt19937_64& rng,
                                                    double margin_px = 10.0);

// Image points of the pattern seen at T_cam_target by `camera` (cv::projectPoints with K and
// kc), plus N(0, noise_px^2) on each coordinate.
std::vector<cv::Point2f> project_pattern(const vision::CameraModel& camera,
                                         const Eigen::Isometry3d& T_cam_target,
                                         const vision::CalibrationPattern& pattern, double noise_px,
                                         std::mt19937_64& rng);

// Stereo views of the poses with the given noise; view names "view00", "view01", ...
std::vector<vision::StereoPatternView> stereo_views(const SyntheticRig& rig,
                                                    const vision::CalibrationPattern& pattern,
                                                    const std::vector<Eigen::Isometry3d>& poses,
                                                    double noise_px, std::mt19937_64& rng);

}  // namespace telear::test
