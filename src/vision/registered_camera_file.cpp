#include "telear/vision/registered_camera_file.hpp"

#include <iomanip>
#include <sstream>

#include "telear/vision/calibration_file.hpp"
#include "telear/vision/registration.hpp"

namespace telear::vision {
namespace {

// An OpenCV FileStorage matrix entry (rows x cols, row-major data), as cv::FileStorage
// writes it, so OpenCV programs and load_stereo_geometry() read the appended keys.
std::string matrix_entry(const std::string& key, int rows, int cols, const double* data) {
  std::ostringstream s;
  s << std::setprecision(17);
  s << key << ": !!opencv-matrix\n   rows: " << rows << "\n   cols: " << cols
    << "\n   dt: d\n   data: [ ";
  for (int i = 0; i < rows * cols; ++i) s << data[i] << (i + 1 == rows * cols ? " ]\n" : ", ");
  return s.str();
}

}  // namespace

Result<Eigen::Isometry3d> stereo_pair_geometry(const std::string& path, const CameraFile& file) {
  Eigen::Isometry3d T_right_left = Eigen::Isometry3d::Identity();
  if (auto geometry = load_stereo_geometry(path)) {
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) T_right_left.linear()(r, c) = geometry->R(r, c);
      T_right_left.translation()(r) = geometry->T(r);
    }
    return T_right_left;
  } else if (file.is_stereo() && file.left_has_pose && file.right_has_pose) {
    return right_from_left(file.left.T_cam_base, file.right->T_cam_base);
  } else {
    return Error{geometry.error().message +
                 ", and the file has no T_cam_base for both eyes either"};
  }
}

std::string registered_camera_yaml(const StereoCameraModel& registered,
                                   const Eigen::Isometry3d& T_right_left) {
  const Eigen::Matrix<double, 3, 3, Eigen::RowMajor> R = T_right_left.linear();
  const Eigen::Vector3d T = T_right_left.translation();
  std::string text = opencv_stereo_camera_yaml(registered);
  text += "# Stereo geometry the registration held fixed: X_R = R X_L + T (metres).\n";
  text += matrix_entry("R", 3, 3, R.data());
  text += matrix_entry("T", 3, 1, T.data());
  return text;
}

Result<StereoCameraModel> load_registered_pair(const std::string& path, const std::string& option) {
  auto file = load_camera_file(path);
  if (!file) return Error{option + ": " + file.error().message};
  if (!file->is_stereo()) {
    return Error{option + " '" + path + "' is a mono camera file; give a stereo one"};
  }
  if (!file->left_has_pose || !file->right_has_pose) {
    return Error{option + " '" + path +
                 "' has no T_cam_base for both eyes (register it first: telear register)"};
  }
  return StereoCameraModel{file->left, *file->right};
}

}  // namespace telear::vision
