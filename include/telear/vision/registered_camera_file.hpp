#pragma once
// The stereo camera file of a registration (docs/registration.md): reading the pair's
// geometry from a calibration, writing the registered file, reading a registered one back.
//
// T_right_left maps left-camera coordinates to right-camera ones (X_R = R X_L + T, metres).
// A stereo `telear calibrate` file has it as its R, T keys; a file that already has
// T_cam_base for both eyes (a registered file, a simulator's truth.yaml) gives it as
// T_right_base T_left_base^-1. The registered file is the camera file with T_cam_base set for
// both eyes plus R and T, so it can be registered again; a calibration's other stereo keys
// (E, F, the rectification) are not carried over.

#include <Eigen/Geometry>
#include <string>

#include "telear/core/result.hpp"
#include "telear/vision/camera_file.hpp"

namespace telear::vision {

// T_right_left of the stereo file `path` (already loaded as `file`). Errors name the file
// and say that neither R, T nor both T_cam_base are there.
Result<Eigen::Isometry3d> stereo_pair_geometry(const std::string& path, const CameraFile& file);

// The registered camera file's text (OpenCV FileStorage YAML): `registered` with both
// T_cam_base, then R and T of `T_right_left`.
std::string registered_camera_yaml(const StereoCameraModel& registered,
                                   const Eigen::Isometry3d& T_right_left);

// A stereo camera file with both poses (a registered file or a truth.yaml), or an error that
// starts with `option` (the CLI option or role that named the file) and says how to fix it.
Result<StereoCameraModel> load_registered_pair(const std::string& path, const std::string& option);

}  // namespace telear::vision
