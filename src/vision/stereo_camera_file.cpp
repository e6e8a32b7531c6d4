#include "telear/vision/stereo_camera_file.hpp"

#include "telear/vision/camera_file.hpp"

namespace telear::vision {

Result<StereoCameraModel> load_stereo_cameras(const std::string& path) {
  auto file = load_camera_file(path);
  if (!file) return file.error();
  if (!file->right) return Error{"calibration '" + path + "': not a stereo camera file"};
  return StereoCameraModel{file->left, *file->right};
}

}  // namespace telear::vision
