#include "telear/vision/camera_file.hpp"

#include "telear/core/image_size.hpp"
#include "telear/core/yaml_reader.hpp"

#include <yaml-cpp/yaml.h>

#include <sys/stat.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <opencv2/core.hpp>
#include <optional>
#include <sstream>
#include <vector>

namespace telear::vision {
namespace {

std::string join(const std::string& prefix, const std::string& key) {
  return prefix.empty() ? key : prefix + "." + key;
}

int integer_field(const YAML::Node& node, const std::string& what) {
  if (!node) throw core::YamlFieldError{what + ": missing"};
  if (!node.IsScalar()) throw core::YamlFieldError{what + ": must be an integer"};
  try {
    return node.as<int>();
  } catch (const YAML::Exception&) {
    throw core::YamlFieldError{what + ": must be an integer, got '" + node.Scalar() + "'"};
  }
}

struct Matrix {
  int rows = 0;
  int cols = 0;
  std::vector<double> data;  // row-major
};

// An OpenCV / ROS matrix {rows, cols, data: [...]} (dt, when present, is not needed: the
// values are read as doubles), or a plain list of numbers (rows = 1).
Matrix matrix(const YAML::Node& node, const std::string& what) {
  if (!node) throw core::YamlFieldError{what + ": missing"};
  Matrix m;
  YAML::Node data;
  if (node.IsSequence()) {
    data = node;
    m.rows = 1;
    m.cols = static_cast<int>(node.size());
  } else if (node.IsMap()) {
    m.rows = integer_field(node["rows"], what + ".rows");
    m.cols = integer_field(node["cols"], what + ".cols");
    if (m.rows <= 0 || m.cols <= 0 || m.rows > 64 || m.cols > 64) {
      throw core::YamlFieldError{what + ": rows and cols must be in [1, 64], got " +
                                 std::to_string(m.rows) + "x" + std::to_string(m.cols)};
    }
    data = node["data"];
    if (!data) throw core::YamlFieldError{what + ".data: missing"};
    if (!data.IsSequence()) throw core::YamlFieldError{what + ".data: must be a list of numbers"};
    if (data.size() != static_cast<size_t>(m.rows * m.cols)) {
      throw core::YamlFieldError{what + ".data: expected " + std::to_string(m.rows * m.cols) +
                                 " numbers (" + std::to_string(m.rows) + "x" +
                                 std::to_string(m.cols) + "), got " + std::to_string(data.size())};
    }
  } else {
    throw core::YamlFieldError{what + ": must be a matrix {rows, cols, data} or a list of numbers"};
  }
  for (size_t i = 0; i < data.size(); ++i) {
    m.data.push_back(core::number_or_throw(data[i], what + ".data[" + std::to_string(i) + "]"));
  }
  return m;
}

std::string format_shape(const Matrix& m) {
  return std::to_string(m.rows) + "x" + std::to_string(m.cols);
}

std::string format_number(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.3g", value);
  return buffer;
}

// A rotation matrix as files carry it. Files typed by hand carry rotations to ~6 decimals;
// accept those and snap to the nearest rotation, so that downstream checks at 1e-6 hold.
// `part` says what in `what` must be a rotation ("the rotation part" of a transform).
Eigen::Matrix3d rotation(const Eigen::Matrix3d& R, const std::string& what,
                         const std::string& part) {
  const double orthonormality = (R * R.transpose() - Eigen::Matrix3d::Identity()).norm();
  if (!(orthonormality <= 1e-4)) {
    throw core::YamlFieldError{what + ": " + part + " is not orthonormal (|R R^T - I| = " +
                               format_number(orthonormality) + ")"};
  }
  if (R.determinant() < 0.0) {
    throw core::YamlFieldError{what + ": " + part + " is a reflection (determinant -1)"};
  }
  return Eigen::Quaterniond(R).normalized().toRotationMatrix();
}

// A 3x3 matrix {rows: 3, cols: 3, data} or a list of 9 numbers, row-major.
Eigen::Matrix3d matrix3(const YAML::Node& node, const std::string& what) {
  const Matrix m = matrix(node, what);
  if (m.data.size() != 9 || (m.rows != 3 && m.rows != 1)) {
    throw core::YamlFieldError{what + ": expected a 3x3 matrix, got " + format_shape(m)};
  }
  Eigen::Matrix3d M;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) M(r, c) = m.data[static_cast<size_t>(3 * r + c)];
  }
  return M;
}

Eigen::Isometry3d rigid_transform(const YAML::Node& node, const std::string& what) {
  const Matrix m = matrix(node, what);
  if (m.data.size() != 16 || (m.rows != 4 && m.rows != 1)) {
    throw core::YamlFieldError{what + ": expected a 4x4 matrix, got " + format_shape(m)};
  }
  Eigen::Matrix4d T;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) T(r, c) = m.data[static_cast<size_t>(4 * r + c)];
  }
  if ((T.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > 1e-9) {
    throw core::YamlFieldError{what + ": the last row must be 0 0 0 1"};
  }
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = rotation(T.topLeftCorner<3, 3>(), what, "the rotation part");
  pose.translation() = T.topRightCorner<3, 1>();
  return pose;
}

// The lens model (ROS's distortion_model, plumb_bob when absent) and its D vector. OpenCV's
// calibrateCamera writes 4, 5, 8, 12 or 14 coefficients for plumb_bob / rational files; the
// thin-prism and tilt terms beyond the eighth must be zero (telear does not model them), and a
// plumb_bob file's k4..k6 too.
Distortion distortion(const YAML::Node& map, const std::string& prefix) {
  const std::string what = join(prefix, "distortion_coefficients");
  DistortionModel model = DistortionModel::plumb_bob;
  if (const YAML::Node node = map["distortion_model"]) {
    const std::string name = node.IsScalar() ? node.Scalar() : "";
    auto parsed = parse_distortion_model(name);
    if (!parsed)
      throw core::YamlFieldError{join(prefix, "distortion_model") + ": " + parsed.error().message};
    model = *parsed;
  }
  const YAML::Node node = map["distortion_coefficients"];
  if (!node) {  // a lens without distortion may leave the key out
    Distortion none;
    none.model = model;
    return none;
  }
  const Matrix m = matrix(node, what);
  if (m.rows != 1 && m.cols != 1) {
    throw core::YamlFieldError{what + ": expected a vector (1xN or Nx1), got " + format_shape(m)};
  }
  const size_t n = m.data.size();
  if (model == DistortionModel::equidistant) {
    if (n != 4) {
      throw core::YamlFieldError{
          what + ": equidistant takes 4 coefficients (k1, k2, k3, k4), got " + std::to_string(n)};
    }
    return *Distortion::from_coefficients(model, m.data);
  }
  if (n != 4 && n != 5 && n != 8 && n != 12 && n != 14) {
    throw core::YamlFieldError{what + ": expected 4, 5, 8, 12 or 14 coefficients, got " +
                               std::to_string(n)};
  }
  const size_t used = model == DistortionModel::rational_polynomial ? 8 : 5;
  if (model == DistortionModel::rational_polynomial && n < 8) {
    throw core::YamlFieldError{
        what +
        ": rational_polynomial takes 8 coefficients (k1, k2, p1, p2, k3, k4, "
        "k5, k6), got " +
        std::to_string(n)};
  }
  for (size_t i = used; i < n; ++i) {
    if (m.data[i] != 0.0) {
      throw core::YamlFieldError{what + ": coefficient " + std::to_string(i) + " is not zero; " +
                                 distortion_model_name(model) +
                                 (model == DistortionModel::plumb_bob
                                      ? " models k1, k2, p1, p2, k3 only (set distortion_model: "
                                        "rational_polynomial for k4..k6)"
                                      : " models k1, k2, p1, p2, k3, k4, k5, k6 only")};
    }
  }
  std::vector<double> d(m.data.begin(), m.data.begin() + static_cast<long>(std::min(n, used)));
  while (d.size() < used) d.push_back(0.0);
  return *Distortion::from_coefficients(model, d);
}

// A ROS camera_info file's rectification_matrix and projection_matrix (both or neither).
std::optional<Rectification> rectification(const YAML::Node& map, const std::string& prefix) {
  const YAML::Node r_node = map["rectification_matrix"];
  const YAML::Node p_node = map["projection_matrix"];
  if (!r_node && !p_node) return std::nullopt;
  const std::string r_what = join(prefix, "rectification_matrix");
  const std::string p_what = join(prefix, "projection_matrix");
  if (!r_node || !p_node) {
    throw core::YamlFieldError{(r_node ? p_what : r_what) +
                               ": missing (a ROS camera_info file gives rectification_matrix and "
                               "projection_matrix together)"};
  }
  Rectification rect;
  rect.R = rotation(matrix3(r_node, r_what), r_what, "the matrix");
  const Matrix m = matrix(p_node, p_what);
  if (m.data.size() != 12 || (m.rows != 3 && m.rows != 1)) {
    throw core::YamlFieldError{p_what + ": expected a 3x4 matrix, got " + format_shape(m)};
  }
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) rect.P(r, c) = m.data[static_cast<size_t>(4 * r + c)];
  }
  if ((rect.P.row(2) - Eigen::RowVector4d(0, 0, 1, 0)).cwiseAbs().maxCoeff() > 1e-12) {
    throw core::YamlFieldError{p_what + ": the last row must be 0 0 1 0, got " +
                               format_number(rect.P(2, 0)) + " " + format_number(rect.P(2, 1)) +
                               " " + format_number(rect.P(2, 2)) + " " +
                               format_number(rect.P(2, 3))};
  }
  if (rect.P(1, 0) != 0.0) throw core::YamlFieldError{p_what + ": [1][0] must be 0"};
  if (!(rect.P(0, 0) > 0.0)) throw core::YamlFieldError{p_what + ": fx' ([0][0]) must be positive"};
  if (!(rect.P(1, 1) > 0.0)) throw core::YamlFieldError{p_what + ": fy' ([1][1]) must be positive"};
  return rect;
}

struct ParsedCamera {
  CameraModel camera;
  bool has_pose = false;
  std::optional<Rectification> rectification;
  std::string name;  // camera_name
};

ParsedCamera camera(const YAML::Node& map, const std::string& prefix) {
  if (!map.IsMap()) {
    throw core::YamlFieldError{(prefix.empty() ? std::string("the file") : prefix) +
                               ": must be a map of image_width, image_height, camera_matrix, ..."};
  }
  ParsedCamera parsed;
  CameraModel& c = parsed.camera;
  c.width = integer_field(map["image_width"], join(prefix, "image_width"));
  c.height = integer_field(map["image_height"], join(prefix, "image_height"));

  const std::string k_what = join(prefix, "camera_matrix");
  const Matrix K = matrix(map["camera_matrix"], k_what);
  if (K.data.size() != 9 || (K.rows != 3 && K.rows != 1)) {
    throw core::YamlFieldError{k_what + ": expected a 3x3 matrix, got " + format_shape(K)};
  }
  const std::vector<double>& k = K.data;
  if (k[3] != 0.0 || k[6] != 0.0 || k[7] != 0.0 || std::abs(k[8] - 1.0) > 1e-12) {
    throw core::YamlFieldError{
        k_what +
        ": must be [fx s cx; 0 fy cy; 0 0 1] ([1][0], [2][0], [2][1] zero and "
        "[2][2] one)"};
  }
  if (!(k[0] > 0.0)) throw core::YamlFieldError{k_what + ": fx ([0][0]) must be positive"};
  if (!(k[4] > 0.0)) throw core::YamlFieldError{k_what + ": fy ([1][1]) must be positive"};
  c.fx = k[0];
  c.alpha_c = k[1] / k[0];
  c.cx = k[2];
  c.fy = k[4];
  c.cy = k[5];
  c.kc = distortion(map, prefix);
  parsed.rectification = rectification(map, prefix);
  if (const YAML::Node name = map["camera_name"]; name && name.IsScalar()) {
    parsed.name = name.Scalar();
  }
  if (const YAML::Node pose = map["T_cam_base"]) {
    c.T_cam_base = rigid_transform(pose, join(prefix, "T_cam_base"));
    parsed.has_pose = true;
  }
  if (Status valid = validate_camera(c); !valid) {
    throw core::YamlFieldError{(prefix.empty() ? "" : prefix + ": ") + valid.error().message};
  }
  return parsed;
}

// OpenCV writes the non-standard directive "%YAML:1.0", which YAML parsers reject; blank it
// (keeping line numbers for messages).
std::string strip_opencv_directive(const std::string& text) {
  if (text.rfind("%YAML:", 0) != 0) return text;
  const size_t end = text.find('\n');
  return end == std::string::npos ? std::string() : text.substr(end);
}

std::string read_file(const std::string& path, bool& ok) {
  std::ifstream in(path, std::ios::binary);
  ok = static_cast<bool>(in);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

cv::Mat mat(const Eigen::Matrix3d& K) {
  cv::Mat m(3, 3, CV_64F);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) m.at<double>(r, c) = K(r, c);
  }
  return m;
}

void write_camera(cv::FileStorage& fs, const CameraModel& camera) {
  fs << "image_width" << camera.width;
  fs << "image_height" << camera.height;
  fs << "camera_matrix" << mat(camera.K());
  std::vector<double> kc = camera.kc.coefficients();
  // Named even for plumb_bob, the readers' default: a reader that does not default (ROS
  // tools, people) sees which model the D vector belongs to.
  fs << "distortion_model" << distortion_model_name(camera.kc.model);
  fs << "distortion_coefficients" << cv::Mat(1, static_cast<int>(kc.size()), CV_64F, kc.data());
  cv::Mat T(4, 4, CV_64F);
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) T.at<double>(r, c) = camera.T_cam_base.matrix()(r, c);
  }
  fs << "T_cam_base" << T;
}

Status write_text(const std::string& text, const std::string& path) {
  std::ofstream out(path, std::ios::binary);
  if (!out) return Error{"cannot write camera file '" + path + "'"};
  out << text;
  out.close();
  if (!out) return Error{"cannot write camera file '" + path + "'"};
  return Status::Ok();
}

// A stereo calibration file's R and T (X_R = R X_L + T, stereo_calibration.hpp), when given.
std::optional<Eigen::Isometry3d> stereo_geometry(const YAML::Node& root) {
  if (!root["R"] && !root["T"]) return std::nullopt;
  if (!root["R"]) throw core::YamlFieldError{"R: missing (a stereo file's geometry needs R and T)"};
  if (!root["T"]) throw core::YamlFieldError{"T: missing (a stereo file's geometry needs R and T)"};
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = rotation(matrix3(root["R"], "R"), "R", "the matrix");
  const Matrix t = matrix(root["T"], "T");
  if (t.data.size() != 3 || (t.rows != 1 && t.cols != 1)) {
    throw core::YamlFieldError{"T: expected a vector of 3 values, got " + format_shape(t)};
  }
  T.translation() = Eigen::Vector3d(t.data[0], t.data[1], t.data[2]);
  return T;
}

void set_left(CameraFile& file, ParsedCamera parsed) {
  file.left = parsed.camera;
  file.left_has_pose = parsed.has_pose;
  file.left_rectification = parsed.rectification;
  file.left_name = parsed.name;
}

void set_right(CameraFile& file, ParsedCamera parsed) {
  file.right = parsed.camera;
  file.right_has_pose = parsed.has_pose;
  file.right_rectification = parsed.rectification;
  file.right_name = parsed.name;
}

bool is_regular_file(const std::string& path) {
  struct stat info {};
  return ::stat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode);
}

std::string storage_text(OpenCvStorageFormat format,
                         const std::function<void(cv::FileStorage&)>& write) {
  cv::FileStorage fs(format == OpenCvStorageFormat::xml ? ".xml" : ".yaml",
                     cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
  write(fs);
  return fs.releaseAndGetString();
}

}  // namespace

Result<CameraFile> parse_camera_yaml(const std::string& text, const std::string& source) {
  const std::string where = "camera file '" + source + "': ";
  std::string yaml = text;
  if (is_xml_text(text)) {
    // One parser for both layouts: cv::FileStorage rewrites the XML as its YAML.
    auto converted = convert_opencv_storage(text, OpenCvStorageFormat::yaml);
    if (!converted) return Error{where + converted.error().message};
    yaml = std::move(*converted);
  }
  const auto loaded = core::load_yaml(strip_opencv_directive(yaml), where);
  if (!loaded) return loaded.error();
  return core::catch_yaml_errors<CameraFile>(where, [&] {
    const YAML::Node& root = *loaded;
    if (!root.IsMap()) throw core::YamlFieldError{"the file must be a YAML map"};
    CameraFile file;
    if (root["left"] || root["right"]) {
      if (!root["left"])
        throw core::YamlFieldError{"left: missing (a stereo file needs left and right)"};
      if (!root["right"])
        throw core::YamlFieldError{"right: missing (a stereo file needs left and right)"};
      set_left(file, camera(root["left"], "left"));
      set_right(file, camera(root["right"], "right"));
      file.T_right_left = stereo_geometry(root);
    } else {
      set_left(file, camera(root, ""));
    }
    return file;
  });
}

Result<CameraFile> load_camera_file(const std::string& path) {
  if (const auto comma = path.find(','); comma != std::string::npos && !is_regular_file(path) &&
                                         path.find(',', comma + 1) == std::string::npos) {
    return load_stereo_camera_files(path.substr(0, comma), path.substr(comma + 1));
  }
  bool ok = false;
  const std::string text = read_file(path, ok);
  if (!ok) return Error{"cannot open camera file '" + path + "'"};
  if (opencv_storage_format_of_path(path) == OpenCvStorageFormat::xml && !is_xml_text(text)) {
    return Error{"camera file '" + path +
                 "': not valid OpenCV FileStorage XML: the text does not start with '<'"};
  }
  return parse_camera_yaml(text, path);
}

Result<CameraFile> load_stereo_camera_files(const std::string& left_path,
                                            const std::string& right_path) {
  Result<CameraFile> left = load_camera_file(left_path);
  if (!left) return left.error();
  Result<CameraFile> right = load_camera_file(right_path);
  if (!right) return right.error();
  if (left->is_stereo()) {
    return Error{"camera file '" + left_path + "': is a stereo file; give one camera per file"};
  }
  if (right->is_stereo()) {
    return Error{"camera file '" + right_path + "': is a stereo file; give one camera per file"};
  }
  // Two ROS camera_info files not registered to the robot: a rectified pair, whose R and P
  // are the only statement of the baseline.
  if (left->left_rectification && right->left_rectification && !left->left_has_pose &&
      !right->left_has_pose) {
    return load_ros_stereo_pair(left_path, right_path);
  }
  CameraFile file;
  file.left = left->left;
  file.left_has_pose = left->left_has_pose;
  file.left_rectification = left->left_rectification;
  file.left_name = left->left_name;
  file.right = right->left;
  file.right_has_pose = right->left_has_pose;
  file.right_rectification = right->left_rectification;
  file.right_name = right->left_name;
  return file;
}

Result<CameraFile> load_ros_stereo_pair(const std::string& left_path,
                                        const std::string& right_path) {
  Result<CameraFile> left = load_camera_file(left_path);
  if (!left) return left.error();
  Result<CameraFile> right = load_camera_file(right_path);
  if (!right) return right.error();
  const auto check = [](const CameraFile& file, const std::string& path) -> Status {
    if (file.is_stereo()) {
      return Error{"camera file '" + path + "': is a stereo file; give one camera per file"};
    }
    if (!file.left_rectification) {
      return Error{"camera file '" + path +
                   "': rectification_matrix and projection_matrix: missing (not a ROS "
                   "camera_info file of a stereo pair)"};
    }
    return Status::Ok();
  };
  if (Status s = check(*left, left_path); !s) return s.error();
  if (Status s = check(*right, right_path); !s) return s.error();
  const std::string where = "stereo pair '" + left_path + "', '" + right_path + "': ";
  const CameraModel& l = left->left;
  const CameraModel& r = right->left;
  if (l.width != r.width || l.height != r.height) {
    return Error{where + "the two files disagree in image size: left " +
                 core::to_string(core::ImageSize{l.width, l.height}) + ", right " +
                 core::to_string(core::ImageSize{r.width, r.height}) +
                 " (one rectified pair has one image size)"};
  }
  if (l.kc.model != r.kc.model) {
    return Error{where + "the two files disagree in distortion_model: left " +
                 distortion_model_name(l.kc.model) + ", right " +
                 distortion_model_name(r.kc.model)};
  }
  auto T_right_left =
      right_from_left_rectified(*left->left_rectification, *right->left_rectification);
  if (!T_right_left) return Error{where + T_right_left.error().message};
  CameraFile file;
  file.left = l;
  file.left.T_cam_base = Eigen::Isometry3d::Identity();
  file.left_rectification = left->left_rectification;
  file.left_name = left->left_name;
  file.right = r;
  file.right->T_cam_base = *T_right_left;
  file.right_rectification = right->left_rectification;
  file.right_name = right->left_name;
  file.T_right_left = *T_right_left;
  return file;
}

std::string opencv_camera_text(const CameraModel& camera, OpenCvStorageFormat format) {
  return storage_text(format, [&camera](cv::FileStorage& fs) { write_camera(fs, camera); });
}

std::string opencv_stereo_camera_text(const StereoCameraModel& cameras,
                                      OpenCvStorageFormat format) {
  return storage_text(format, [&cameras](cv::FileStorage& fs) {
    fs << "left"
       << "{";
    write_camera(fs, cameras.left);
    fs << "}";
    fs << "right"
       << "{";
    write_camera(fs, cameras.right);
    fs << "}";
  });
}

std::string opencv_camera_yaml(const CameraModel& camera) {
  return opencv_camera_text(camera, OpenCvStorageFormat::yaml);
}

std::string opencv_stereo_camera_yaml(const StereoCameraModel& cameras) {
  return opencv_stereo_camera_text(cameras, OpenCvStorageFormat::yaml);
}

Status write_camera_file(const CameraModel& camera, const std::string& path) {
  return write_text(opencv_camera_text(camera, opencv_storage_format_of_path(path)), path);
}

Status write_stereo_camera_file(const StereoCameraModel& cameras, const std::string& path) {
  return write_text(opencv_stereo_camera_text(cameras, opencv_storage_format_of_path(path)), path);
}

std::string ros_camera_info_yaml(const CameraModel& camera, const std::string& camera_name) {
  auto matrix_node = [](int rows, int cols, const std::vector<double>& data) {
    YAML::Node node;
    node["rows"] = rows;
    node["cols"] = cols;
    YAML::Node values(YAML::NodeType::Sequence);
    for (double v : data) values.push_back(v);
    values.SetStyle(YAML::EmitterStyle::Flow);
    node["data"] = values;
    return node;
  };
  const Eigen::Matrix3d K = camera.K();
  std::vector<double> k, p, t;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) k.push_back(K(r, c));
    for (int c = 0; c < 4; ++c) p.push_back(c < 3 ? K(r, c) : 0.0);
  }
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) t.push_back(camera.T_cam_base.matrix()(r, c));
  }
  const std::vector<double> kc = camera.kc.coefficients();
  YAML::Emitter out;
  out.SetDoublePrecision(17);
  YAML::Node root;
  root["image_width"] = camera.width;
  root["image_height"] = camera.height;
  root["camera_name"] = camera_name;
  root["camera_matrix"] = matrix_node(3, 3, k);
  root["distortion_model"] = distortion_model_name(camera.kc.model);
  root["distortion_coefficients"] = matrix_node(1, static_cast<int>(kc.size()), kc);
  root["rectification_matrix"] = matrix_node(3, 3, {1, 0, 0, 0, 1, 0, 0, 0, 1});
  root["projection_matrix"] = matrix_node(3, 4, p);
  root["T_cam_base"] = matrix_node(4, 4, t);
  out << root;
  return std::string(out.c_str()) + "\n";
}

}  // namespace telear::vision
