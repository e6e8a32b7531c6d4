#pragma once
// The stereo calibration an operator's view draws with (`telear console --calibration`,
// `telear web --calibration`): a camera file in any layout load_camera_file() reads, holding
// both eyes.

#include <string>

#include "telear/core/result.hpp"
#include "telear/vision/camera_model.hpp"

namespace telear::vision {

// The file's two cameras; an error naming the file when it holds one ("calibration 'c.yaml':
// not a stereo camera file"), or load_camera_file()'s.
Result<StereoCameraModel> load_stereo_cameras(const std::string& path);

}  // namespace telear::vision
