#include "telear/vision/calibration_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <opencv2/core/persistence.hpp>

#include "telear/vision/camera_file.hpp"
#include "telear/vision/opencv_storage.hpp"

namespace telear::vision {
namespace {

// The camera keys of docs/cameras.md without T_cam_base: a calibrated camera that is not yet
// registered to the robot (camera_file.hpp's writer always writes a pose).
void write_intrinsics(cv::FileStorage& fs, const CameraModel& camera) {
  const Eigen::Matrix3d K = camera.K();
  cv::Mat k(3, 3, CV_64F);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) k.at<double>(r, c) = K(r, c);
  }
  std::vector<double> kc = camera.kc.coefficients();
  fs << "image_width" << camera.width;
  fs << "image_height" << camera.height;
  fs << "camera_matrix" << k;
  fs << "distortion_model" << distortion_model_name(camera.kc.model);
  fs << "distortion_coefficients" << cv::Mat(1, static_cast<int>(kc.size()), CV_64F, kc.data());
}

std::string directory_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

std::string ros_matrix(const char* key, int rows, int cols, const double* data) {
  std::string text = std::string(key) + ":\n  rows: " + std::to_string(rows) +
                     "\n  cols: " + std::to_string(cols) + "\n  data: [";
  char number[40];
  for (int i = 0; i < rows * cols; ++i) {
    std::snprintf(number, sizeof number, "%s%.17g", i == 0 ? "" : ", ", data[i]);
    text += number;
  }
  return text + "]\n";
}

std::string system_error(int error) {
  return std::strerror(error);
}

// Writes `text` to a new file next to `path`; returns its name or an error.
Result<std::string> write_temporary(const std::string& path, const std::string& text) {
  static int counter = 0;
  const std::string directory = directory_of(path);
  const std::string base =
      path.substr(path.find_last_of('/') == std::string::npos ? 0 : path.find_last_of('/') + 1);
  for (int attempt = 0; attempt < 100; ++attempt) {
    const std::string temporary = directory + "/." + base + ".tmp-" + std::to_string(::getpid()) +
                                  "-" + std::to_string(counter++);
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0 && errno == EEXIST) continue;
    if (fd < 0) {
      return Error{"cannot write '" + path + "': " + system_error(errno) +
                   "; choose a writable directory"};
    }
    std::size_t written = 0;
    while (written < text.size()) {
      const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        const int error = errno;
        ::close(fd);
        ::unlink(temporary.c_str());
        return Error{"cannot write '" + path + "': " + system_error(error) +
                     "; free some disk space or choose another directory"};
      }
      written += static_cast<std::size_t>(n);
    }
    if (::close(fd) != 0) {
      const int error = errno;
      ::unlink(temporary.c_str());
      return Error{"cannot write '" + path + "': " + system_error(error)};
    }
    return temporary;
  }
  return Error{"cannot write '" + path + "': cannot create a temporary file beside it"};
}

}  // namespace

std::string mono_calibration_yaml(const MonoCalibration& calibration,
                                  const CalibrationPattern& pattern) {
  cv::FileStorage fs(".yaml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
  write_intrinsics(fs, calibration.camera);
  fs << "rms_px" << calibration.rms_px;
  fs << "calibration_pattern" << pattern.spec();
  return fs.releaseAndGetString();
}

std::string stereo_calibration_yaml(const StereoCalibration& c, const CalibrationPattern& pattern) {
  cv::FileStorage fs(".yaml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
  fs << "left"
     << "{";
  write_intrinsics(fs, c.cameras.left);
  fs << "}";
  fs << "right"
     << "{";
  write_intrinsics(fs, c.cameras.right);
  fs << "}";
  fs << "R" << cv::Mat(c.R);
  fs << "T" << cv::Mat(c.T);
  fs << "E" << cv::Mat(c.E);
  fs << "F" << cv::Mat(c.F);
  fs << "R1" << cv::Mat(c.rectification.R1);
  fs << "R2" << cv::Mat(c.rectification.R2);
  fs << "P1" << cv::Mat(c.rectification.P1);
  fs << "P2" << cv::Mat(c.rectification.P2);
  fs << "Q" << cv::Mat(c.rectification.Q);
  fs << "rms_px" << c.rms_px;
  fs << "calibration_pattern" << pattern.spec();
  return fs.releaseAndGetString();
}

std::string rectified_camera_info_yaml(const CameraModel& camera, const cv::Matx33d& R,
                                       const cv::Matx34d& P, const std::string& camera_name) {
  const Eigen::Matrix3d K = camera.K();
  double k[9];
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) k[3 * r + c] = K(r, c);
  }
  const std::vector<double> kc = camera.kc.coefficients();
  return "image_width: " + std::to_string(camera.width) +
         "\nimage_height: " + std::to_string(camera.height) + "\ncamera_name: " + camera_name +
         "\n" + ros_matrix("camera_matrix", 3, 3, k) +
         "distortion_model: " + distortion_model_name(camera.kc.model) + "\n" +
         ros_matrix("distortion_coefficients", 1, static_cast<int>(kc.size()), kc.data()) +
         ros_matrix("rectification_matrix", 3, 3, R.val) +
         ros_matrix("projection_matrix", 3, 4, P.val);
}

std::string ros_mono_camera_info_yaml(const MonoCalibration& calibration,
                                      const std::string& camera_name) {
  const CameraModel& camera = calibration.camera;
  const cv::Matx34d P(camera.fx, camera.skew(), camera.cx, 0.0, 0.0, camera.fy, camera.cy, 0.0, 0.0,
                      0.0, 1.0, 0.0);
  return rectified_camera_info_yaml(camera, cv::Matx33d::eye(), P, camera_name);
}

std::string ros_stereo_camera_info_yaml(const StereoCalibration& calibration, bool right,
                                        const std::string& camera_name) {
  const StereoRectification& rect = calibration.rectification;
  return rectified_camera_info_yaml(right ? calibration.cameras.right : calibration.cameras.left,
                                    right ? rect.R2 : rect.R1, right ? rect.P2 : rect.P1,
                                    camera_name);
}

Result<StereoGeometry> load_stereo_geometry(const std::string& path) {
  const std::string where = "stereo calibration '" + path + "': ";
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0 || !S_ISREG(info.st_mode)) {
    if (path.find(',') == std::string::npos) return Error{where + "no such file"};
    // "left.yaml,right.yaml": a pair of ROS camera_info files states its geometry in R and P.
    auto pair = load_camera_file(path);
    if (!pair) return Error{where + pair.error().message};
    if (!pair->T_right_left) {
      return Error{where +
                   "the two files do not state the pair's geometry (give ROS camera_info "
                   "files of one rectified pair, without T_cam_base)"};
    }
    StereoGeometry geometry;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) geometry.R(r, c) = pair->T_right_left->linear()(r, c);
      geometry.T(r) = pair->T_right_left->translation()(r);
    }
    return geometry;
  }
  cv::FileStorage fs;
  try {
    if (!fs.open(path, cv::FileStorage::READ)) return Error{where + "cannot open or parse it"};
  } catch (const cv::Exception&) {
    return Error{where + "not an OpenCV YAML file"};
  }
  cv::Mat R, T;
  try {
    fs["R"] >> R;
    fs["T"] >> T;
  } catch (const cv::Exception&) {
    return Error{where + "R or T is not a matrix"};
  }
  if (R.empty() || T.empty()) {
    return Error{where + "no R and T (it is not the output of a stereo `telear calibrate`)"};
  }
  if (R.rows != 3 || R.cols != 3 || T.total() != 3) {
    return Error{where + "R must be 3x3 and T have 3 elements"};
  }
  R.convertTo(R, CV_64F);
  T.convertTo(T, CV_64F);
  if (!cv::checkRange(R) || !cv::checkRange(T)) return Error{where + "R or T is not finite"};
  StereoGeometry geometry;
  geometry.R = cv::Matx33d(R);
  geometry.T = cv::Vec3d(T.at<double>(0), T.at<double>(1), T.at<double>(2));
  if (cv::norm(geometry.R * geometry.R.t() - cv::Matx33d::eye()) > 1e-6 ||
      cv::determinant(geometry.R) < 0.0) {
    return Error{where + "R is not a rotation"};
  }
  return geometry;
}

Status check_output_path(const std::string& path, const std::string& option) {
  if (path.empty()) return Error{option + ": empty file name"};
  struct stat info {};
  if (::stat(path.c_str(), &info) == 0 && S_ISDIR(info.st_mode)) {
    return Error{option + " '" + path + "' is a directory; give a file name, e.g. '" + path +
                 (path.back() == '/' ? "" : "/") + "stereo.yaml'"};
  }
  const std::string directory = directory_of(path);
  if (::stat(directory.c_str(), &info) != 0 || !S_ISDIR(info.st_mode)) {
    return Error{option + " '" + path + "': directory '" + directory +
                 "' does not exist; create it or choose another output path"};
  }
  if (::access(directory.c_str(), W_OK) != 0) {
    return Error{option + " '" + path + "': directory '" + directory + "' is not writable (" +
                 system_error(errno) + "); choose another output path"};
  }
  return Status::Ok();
}

Result<std::string> text_for_path(const std::string& text, const std::string& path) {
  if (opencv_storage_format_of_path(path) != OpenCvStorageFormat::xml) return text;
  if (text.rfind("%YAML", 0) != 0) return text;
  auto xml = convert_opencv_storage(text, OpenCvStorageFormat::xml);
  if (!xml) return Error{"cannot write '" + path + "' as XML: " + xml.error().message};
  return xml;
}

Status write_files_atomically(const std::vector<std::pair<std::string, std::string>>& files) {
  std::vector<std::string> temporaries;
  auto discard = [&temporaries]() {
    for (const std::string& t : temporaries) ::unlink(t.c_str());
  };
  for (const auto& [path, given] : files) {
    auto text = text_for_path(given, path);
    if (!text) {
      discard();
      return text.error();
    }
    auto temporary = write_temporary(path, *text);
    if (!temporary) {
      discard();
      return temporary.error();
    }
    temporaries.push_back(*temporary);
  }
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (std::rename(temporaries[i].c_str(), files[i].first.c_str()) != 0) {
      const int error = errno;
      // The files renamed so far stay (a rename cannot be undone without a backup); the rest
      // are discarded. This needs a target that turned into a directory meanwhile.
      for (std::size_t j = i; j < temporaries.size(); ++j) ::unlink(temporaries[j].c_str());
      return Error{"cannot write '" + files[i].first + "': " + system_error(error)};
    }
  }
  return Status::Ok();
}

}  // namespace telear::vision
