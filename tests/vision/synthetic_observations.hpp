#pragma once
// Registration observations made without rendering: the shipped stereo cameras as the truth,
// a flange marker's corners projected at random configurations where both eyes see them,
// plus Gaussian pixel noise. Shared by the registration, overlay-accuracy and CLI tests.

#include <Eigen/Geometry>
#include <vector>

#include "telear/core/robot_model.hpp"
#include "telear/vision/calibration_pattern.hpp"
#include "telear/vision/camera_model.hpp"
#include "telear/vision/observations_file.hpp"

namespace telear::test {

// data/cameras/puma560_stereo.yaml, both eyes with their T_cam_base (fails the test on error).
vision::StereoCameraModel shipped_stereo_cameras();

// The right camera's pose in the left camera's frame, from the rig's two T_cam_base.
Eigen::Isometry3d T_right_left_of(const vision::StereoCameraModel& rig);

// The 9x6 chessboard of 3 cm squares that the calibration tests render.
vision::CalibrationPattern chessboard_9x6();

// A 5 cm marker 5 cm out along the flange's z axis, corners in cv::aruco's order.
std::vector<Eigen::Vector3d> flange_marker_corners();

// `count` configurations (random within the limits, seeded) at which every point lies at
// least 10 px inside both images, projected by `rig` with N(0, noise_px) noise per axis.
vision::RegistrationObservations synthetic_observations(const core::RobotModel& model,
                                                        const vision::StereoCameraModel& rig,
                                                        const std::vector<Eigen::Vector3d>& points,
                                                        int count, double noise_px, unsigned seed);

}  // namespace telear::test
