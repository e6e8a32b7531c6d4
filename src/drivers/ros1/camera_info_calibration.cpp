#include "drivers/ros1/camera_info_calibration.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "telear/vision/camera_file.hpp"
#include "telear/vision/camera_model.hpp"
#include "telear/vision/rectified_stereo.hpp"

namespace telear::drivers::ros1 {
namespace {

std::string number(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

std::string matrix_yaml(int rows, int cols, const double* data) {
  std::string text =
      "{rows: " + std::to_string(rows) + ", cols: " + std::to_string(cols) + ", data: [";
  for (int i = 0; i < rows * cols; ++i) text += (i ? ", " : "") + number(data[i]);
  return text + "]}";
}

std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

std::string size_text(int width, int height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

// camera_info's D for its distortion_model, as telear's Distortion. Like a camera file, a D
// longer than the model's may only add zeros (OpenCV writes 8, 12 or 14 values).
Result<vision::Distortion> distortion(const CameraInfoFields& info) {
  const bool all_zero =
      std::all_of(info.D.begin(), info.D.end(), [](double d) { return d == 0.0; });
  if (info.distortion_model.empty()) {
    // Drivers of distortion-free (or rectified) images leave both empty.
    if (all_zero) return vision::Distortion{};
    return Error{
        "distortion_model is empty but D is not zero (name the model: plumb_bob, "
        "rational_polynomial or equidistant)"};
  }
  auto model = vision::parse_distortion_model(info.distortion_model);
  if (!model) return Error{"distortion_model: " + model.error().message};
  std::vector<double> d = info.D;
  if (d.empty()) d.assign(vision::distortion_coefficient_count(*model), 0.0);
  if (*model != vision::DistortionModel::equidistant) {
    const std::size_t used = *model == vision::DistortionModel::plumb_bob && d.size() == 4
                                 ? 4
                                 : vision::distortion_coefficient_count(*model);
    for (std::size_t i = used; i < d.size(); ++i) {
      if (d[i] != 0.0) {
        return Error{"D: coefficient " + std::to_string(i) + " is " + number(d[i]) + "; " +
                     info.distortion_model + " has " + std::to_string(used) +
                     " (a lens with k4..k6 is rational_polynomial; thin-prism and tilt terms "
                     "are not modelled)"};
      }
    }
    if (d.size() > used) d.resize(used);
  }
  auto made = vision::Distortion::from_coefficients(*model, d);
  if (!made) return Error{"D: " + made.error().message};
  return *made;
}

// R and P when they describe a rectification (the checks a camera file's reader makes);
// nullopt with the reason otherwise.
std::optional<vision::Rectification> rectification(const CameraInfoFields& info, std::string* why) {
  vision::Rectification rect;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) rect.R(r, c) = info.R[static_cast<std::size_t>(3 * r + c)];
    for (int c = 0; c < 4; ++c) rect.P(r, c) = info.P[static_cast<std::size_t>(4 * r + c)];
  }
  if (rect.P.isZero()) {
    *why = "P is zero";
    return std::nullopt;
  }
  const double orthonormality = (rect.R * rect.R.transpose() - Eigen::Matrix3d::Identity()).norm();
  if (!(orthonormality <= 1e-4) || rect.R.determinant() < 0.0) {
    *why = "R is not a rotation";
    return std::nullopt;
  }
  if ((rect.P.row(2) - Eigen::RowVector4d(0, 0, 1, 0)).cwiseAbs().maxCoeff() > 1e-12 ||
      rect.P(1, 0) != 0.0 || !(rect.P(0, 0) > 0.0) || !(rect.P(1, 1) > 0.0)) {
    *why = "P is not [fx' s cx' Tx; 0 fy' cy' Ty; 0 0 1 0]";
    return std::nullopt;
  }
  return rect;
}

struct Camera {
  vision::CameraModel model;
  std::optional<vision::Rectification> rectification;
};

// nullopt: uncalibrated (a warning says so).
Result<std::optional<Camera>> camera_from_info(const CameraInfoFields& info,
                                               const TopicImageSize& image,
                                               std::vector<std::string>& warnings) {
  const std::string where = "camera_info on " + info.topic + ": ";
  const auto& K = info.K;
  // Uncalibrated: drivers publish K = 0 then, and image_publisher (camera_info_manager with no
  // file) a placeholder with fx = fy = 1, a focal length no camera has.
  if (std::all_of(K.begin(), K.end(), [](double k) { return k == 0.0; }) ||
      (K[0] == 1.0 && K[4] == 1.0)) {
    warnings.push_back(where +
                       "uncalibrated (K is zero, or the placeholder fx = fy = 1): GetCameraInfo "
                       "serves no calibration; calibrate the camera or give --calibration");
    return std::optional<Camera>{};
  }
  if (info.binning_x > 1 || info.binning_y > 1) {
    return Error{where + "binning " +
                 size_text(std::max(info.binning_x, 1), std::max(info.binning_y, 1)) +
                 " is not supported (K is the full sensor's, not the image's); publish "
                 "camera_info for the images as sent, or give --calibration"};
  }
  const bool full_roi = info.roi_x_offset == 0 && info.roi_y_offset == 0 &&
                        ((info.roi_width == 0 && info.roi_height == 0) ||
                         (info.roi_width == info.width && info.roi_height == info.height));
  if (!full_roi) {
    return Error{where + "a region of interest (" + size_text(info.roi_width, info.roi_height) +
                 " at " + std::to_string(info.roi_x_offset) + ", " +
                 std::to_string(info.roi_y_offset) +
                 ") is not supported (K is the full sensor's); publish camera_info for the "
                 "images as sent, or give --calibration"};
  }
  // Some drivers leave the size 0: it is then the images'.
  const bool sized = info.width != 0 || info.height != 0;
  if (sized && (info.width != image.width || info.height != image.height)) {
    return Error{where + "is for " + size_text(info.width, info.height) + " images, but those on " +
                 image.topic + " are " + size_text(image.width, image.height)};
  }
  if (K[3] != 0.0 || K[6] != 0.0 || K[7] != 0.0 || std::abs(K[8] - 1.0) > 1e-12) {
    return Error{where + "K must be [fx s cx; 0 fy cy; 0 0 1]"};
  }
  Camera camera;
  vision::CameraModel& c = camera.model;
  c.width = image.width;
  c.height = image.height;
  c.fx = K[0];
  c.alpha_c = K[0] != 0.0 ? K[1] / K[0] : 0.0;
  c.cx = K[2];
  c.fy = K[4];
  c.cy = K[5];
  auto lens = distortion(info);
  if (!lens) return Error{where + lens.error().message};
  c.kc = *lens;
  if (Status valid = vision::validate_camera(c); !valid) {
    return Error{where + valid.error().message};
  }
  std::string why;
  camera.rectification = rectification(info, &why);
  if (!camera.rectification) {
    warnings.push_back(where + why +
                       ": no rectification, so GetCameraInfo serves no pose between the cameras");
  }
  return std::optional<Camera>(std::move(camera));
}

std::string camera_yaml(const char* key, const CameraInfoFields& info, const Camera& camera) {
  const vision::CameraModel& c = camera.model;
  const Eigen::Matrix3d K = c.K();
  double k[9];
  for (int r = 0; r < 3; ++r) {
    for (int col = 0; col < 3; ++col) k[3 * r + col] = K(r, col);
  }
  const std::vector<double> d = c.kc.coefficients();
  std::string text = std::string(key) + ":\n";
  text += "  camera_name: " + quoted(info.frame_id) + "\n";
  text += "  image_width: " + std::to_string(c.width) + "\n";
  text += "  image_height: " + std::to_string(c.height) + "\n";
  text += "  camera_matrix: " + matrix_yaml(3, 3, k) + "\n";
  text += "  distortion_model: " + std::string(vision::distortion_model_name(c.kc.model)) + "\n";
  text +=
      "  distortion_coefficients: " + matrix_yaml(1, static_cast<int>(d.size()), d.data()) + "\n";
  if (camera.rectification) {
    text += "  rectification_matrix: " + matrix_yaml(3, 3, info.R.data()) + "\n";
    text += "  projection_matrix: " + matrix_yaml(3, 4, info.P.data()) + "\n";
  }
  return text;
}

}  // namespace

Result<CameraInfoCalibration> calibration_from_camera_info(const CameraInfoFields& left,
                                                           const CameraInfoFields& right,
                                                           const TopicImageSize& left_image,
                                                           const TopicImageSize& right_image) {
  CameraInfoCalibration out;
  auto l = camera_from_info(left, left_image, out.warnings);
  if (!l) return l.error();
  auto r = camera_from_info(right, right_image, out.warnings);
  if (!r) return r.error();
  if (!*l || !*r) return out;  // uncalibrated

  std::string pair;
  if ((*l)->rectification && (*r)->rectification) {
    const vision::Rectification& lr = *(*l)->rectification;
    const vision::Rectification& rr = *(*r)->rectification;
    if (rr.tx() == 0.0 && rr.ty() == 0.0) {
      out.warnings.push_back(
          "camera_info on " + right.topic +
          ": P has Tx = Ty = 0, so the cameras are not stated as a rectified pair: GetCameraInfo "
          "serves no pose between them (a stereo --calibration file can give it)");
    } else if (auto T = vision::right_from_left_rectified(lr, rr); !T) {
      out.warnings.push_back("camera_info on " + left.topic + " and " + right.topic + ": " +
                             T.error().message + ": GetCameraInfo serves no pose between them");
    } else {
      // The file's stereo geometry: X_R = R X_L + T (telear/vision/calibration_file.hpp).
      double R[9], t[3];
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) R[3 * i + j] = T->linear()(i, j);
        t[i] = T->translation()(i);
      }
      pair = "R: " + matrix_yaml(3, 3, R) + "\nT: " + matrix_yaml(3, 1, t) + "\n";
    }
  }
  out.yaml =
      "# The stereo calibration of `telear vision-server --source ros`, from ROS camera_info\n"
      "# on " +
      left.topic + " and " + right.topic + " (docs/ros.md, \"Cameras\").\n" +
      camera_yaml("left", left, **l) + camera_yaml("right", right, **r) + pair;
  // What the vision server will read: it must read back (the same checks as any camera file).
  if (auto read = vision::parse_camera_yaml(out.yaml, "camera_info"); !read) {
    return Error{"the calibration from camera_info on " + left.topic + " and " + right.topic +
                 " does not read back: " + read.error().message};
  }
  return out;
}

}  // namespace telear::drivers::ros1
