#include "telear/vision/camera_file.hpp"

#include <gtest/gtest.h>

#include <gmock/gmock.h>

#include <cstdio>
#include <fstream>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <sstream>

#include "telear/core/pose.hpp"
#include "telear/vision/calibration_file.hpp"
#include "telear/vision/opencv_camera.hpp"
#include "test_util/temp_dir.hpp"
#include "test_util/test_util.hpp"

namespace telear::vision {
namespace {

CameraModel camera(double x) {
  CameraModel c;
  c.width = 640;
  c.height = 480;
  c.fx = 812.5123456789;
  c.fy = 809.25;
  c.cx = 331.7;
  c.cy = 236.2;
  c.alpha_c = 0.001;
  c.kc = Distortion::plumb_bob(-0.29, 0.11, 0.0011, -0.0007, -0.02);
  c.T_cam_base = core::pose_from_xyz_rpy({x, -0.2, 1.5}, {2.1, 0.1, -0.3});
  return c;
}

void expect_same(const CameraModel& a, const CameraModel& b) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_LT((a.K() - b.K()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(a.kc.model, b.kc.model);
  EXPECT_EQ(a.kc.coefficients(), b.kc.coefficients());
  EXPECT_LT((a.T_cam_base.matrix() - b.T_cam_base.matrix()).cwiseAbs().maxCoeff(), 1e-12);
}

// `name` in this process's own scratch folder (removed at exit).
std::string temp_path(const std::string& name) {
  static const test_files::TempDir dir("camera_file");
  return dir.file(name);
}

std::string error_of(const std::string& text) {
  Result<CameraFile> r = parse_camera_yaml(text, "cam.yaml");
  EXPECT_FALSE(r.ok()) << text;
  return r.ok() ? "" : r.error().message;
}

const char* kMono = R"(%YAML:1.0
---
image_width: 640
image_height: 480
camera_matrix: !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [ 800., 0., 319.5, 0., 800., 239.5, 0., 0., 1. ]
distortion_coefficients: !!opencv-matrix
   rows: 1
   cols: 5
   dt: d
   data: [ -0.3, 0.1, 0., 0., 0. ]
)";

TEST(CameraFile, OpenCvMonoRoundTripsExactly) {
  const CameraModel c = camera(0.1);
  const std::string path = temp_path("mono.yaml");
  ASSERT_TRUE(write_camera_file(c, path).ok());
  Result<CameraFile> read = load_camera_file(path);
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_FALSE(read->is_stereo());
  EXPECT_TRUE(read->left_has_pose);
  expect_same(read->left, c);
  // OpenCV itself reads the file back.
  cv::FileStorage fs(path, cv::FileStorage::READ);
  cv::Mat K, D, T;
  fs["camera_matrix"] >> K;
  fs["distortion_coefficients"] >> D;
  fs["T_cam_base"] >> T;
  EXPECT_EQ(static_cast<int>(fs["image_width"]), 640);
  EXPECT_DOUBLE_EQ(K.at<double>(0, 0), c.fx);
  EXPECT_DOUBLE_EQ(K.at<double>(0, 1), c.skew());
  EXPECT_DOUBLE_EQ(D.at<double>(0, 4), -0.02);
  EXPECT_DOUBLE_EQ(T.at<double>(0, 3), 0.1);
  std::remove(path.c_str());
}

TEST(CameraFile, StereoInOneFileAndInTwoFiles) {
  const StereoCameraModel pair{camera(0.03), camera(-0.03)};
  const std::string path = temp_path("stereo.yaml");
  ASSERT_TRUE(write_stereo_camera_file(pair, path).ok());
  Result<CameraFile> read = load_camera_file(path);
  ASSERT_TRUE(read.ok()) << read.error().message;
  ASSERT_TRUE(read->is_stereo());
  expect_same(read->left, pair.left);
  expect_same(*read->right, pair.right);

  const std::string l = temp_path("l.yaml"), r = temp_path("r.yaml");
  ASSERT_TRUE(write_camera_file(pair.left, l).ok());
  ASSERT_TRUE(write_camera_file(pair.right, r).ok());
  Result<CameraFile> two = load_stereo_camera_files(l, r);
  ASSERT_TRUE(two.ok()) << two.error().message;
  expect_same(two->left, pair.left);
  expect_same(*two->right, pair.right);
  Result<CameraFile> wrong = load_stereo_camera_files(path, r);
  ASSERT_FALSE(wrong.ok());
  EXPECT_EQ(wrong.error().message,
            "camera file '" + path + "': is a stereo file; give one camera per file");
  for (const std::string& p : {path, l, r}) std::remove(p.c_str());
}

TEST(CameraFile, HandWrittenOpenCvFileWithoutPose) {
  Result<CameraFile> read = parse_camera_yaml(kMono, "cam.yaml");
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_FALSE(read->left_has_pose);
  EXPECT_TRUE(read->left.T_cam_base.isApprox(Eigen::Isometry3d::Identity()));
  EXPECT_DOUBLE_EQ(read->left.kc.k1, -0.3);
  EXPECT_DOUBLE_EQ(read->left.cx, 319.5);
}

TEST(CameraFile, RosCameraInfoRoundTripsAndIsReadWithoutPose) {
  const CameraModel c = camera(0.2);
  Result<CameraFile> read = parse_camera_yaml(ros_camera_info_yaml(c, "left"), "ros.yaml");
  ASSERT_TRUE(read.ok()) << read.error().message;
  expect_same(read->left, c);
  EXPECT_TRUE(read->left_has_pose);

  // What ROS's camera_calibration writes (no T_cam_base, 5 plumb_bob coefficients).
  const char* ros = R"(image_width: 640
image_height: 480
camera_name: narrow_stereo
camera_matrix:
  rows: 3
  cols: 3
  data: [533.0, 0.0, 341.5, 0.0, 533.1, 234.3, 0.0, 0.0, 1.0]
distortion_model: plumb_bob
distortion_coefficients:
  rows: 1
  cols: 5
  data: [-0.288, 0.097, 0.0011, -0.0003, 0.0]
rectification_matrix:
  rows: 3
  cols: 3
  data: [1, 0, 0, 0, 1, 0, 0, 0, 1]
projection_matrix:
  rows: 3
  cols: 4
  data: [533.0, 0.0, 341.5, 0.0, 0.0, 533.1, 234.3, 0.0, 0.0, 0.0, 1.0, 0.0]
)";
  Result<CameraFile> ros_read = parse_camera_yaml(ros, "ros.yaml");
  ASSERT_TRUE(ros_read.ok()) << ros_read.error().message;
  EXPECT_FALSE(ros_read->left_has_pose);
  EXPECT_DOUBLE_EQ(ros_read->left.fy, 533.1);
  EXPECT_DOUBLE_EQ(ros_read->left.kc.p1, 0.0011);
}

TEST(CameraFile, ErrorsNameTheFieldAndWhy) {
  auto with = [](const std::string& from, const std::string& to) {
    std::string text = kMono;
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
  };
  EXPECT_EQ(error_of(with("image_width: 640\n", "")),
            "camera file 'cam.yaml': image_width: missing");
  EXPECT_EQ(error_of(with("image_height: 480", "image_height: big")),
            "camera file 'cam.yaml': image_height: must be an integer, got 'big'");
  EXPECT_EQ(error_of(with("image_height: 480", "image_height: -4")),
            "camera file 'cam.yaml': image_height must be in [1, 16384], got -4");
  EXPECT_EQ(error_of(with("   rows: 3\n   cols: 3", "   rows: 2\n   cols: 3")),
            "camera file 'cam.yaml': camera_matrix.data: expected 6 numbers (2x3), got 9");
  EXPECT_EQ(error_of(with("data: [ 800., 0., 319.5, 0., 800., 239.5, 0., 0., 1. ]",
                          "data: [ 800., 0., 319.5, 0., 800., 239.5, 0., 0., 1., 0, 0, 0 ]")),
            "camera file 'cam.yaml': camera_matrix.data: expected 9 numbers (3x3), got 12");
  EXPECT_EQ(error_of(with("800., 0., 319.5", "800., 0., abc")),
            "camera file 'cam.yaml': camera_matrix.data[2]: must be a number, got 'abc'");
  EXPECT_EQ(error_of(with("800., 0., 319.5", "-800., 0., 319.5")),
            "camera file 'cam.yaml': camera_matrix: fx ([0][0]) must be positive");
  EXPECT_EQ(error_of(with("0., 0., 1. ]", "0., 0., 2. ]")),
            "camera file 'cam.yaml': camera_matrix: must be [fx s cx; 0 fy cy; 0 0 1] ([1][0], "
            "[2][0], [2][1] zero and [2][2] one)");
  EXPECT_EQ(error_of(with("   cols: 5\n   dt: d\n   data: [ -0.3, 0.1, 0., 0., 0. ]",
                          "   cols: 6\n   dt: d\n   data: [ -0.3, 0.1, 0., 0., 0., 0. ]")),
            "camera file 'cam.yaml': distortion_coefficients: expected 4, 5, 8, 12 or 14 "
            "coefficients, got 6");
  EXPECT_EQ(error_of(with("   cols: 5\n   dt: d\n   data: [ -0.3, 0.1, 0., 0., 0. ]",
                          "   cols: 8\n   dt: d\n   data: [ -0.3, 0.1, 0., 0., 0., 0.2, 0, 0 ]")),
            "camera file 'cam.yaml': distortion_coefficients: coefficient 5 is not zero; "
            "plumb_bob models k1, k2, p1, p2, k3 only (set distortion_model: "
            "rational_polynomial for k4..k6)");
  EXPECT_EQ(error_of(with("image_width: 640", "image_width: 640\ndistortion_model: equidistant")),
            "camera file 'cam.yaml': distortion_coefficients: equidistant takes 4 coefficients "
            "(k1, k2, k3, k4), got 5");
  EXPECT_EQ(error_of(with("image_width: 640", "image_width: 640\ndistortion_model: kb8")),
            "camera file 'cam.yaml': distortion_model: unknown distortion model 'kb8' (expected "
            "plumb_bob, rational_polynomial or equidistant)");
  EXPECT_EQ(error_of(with("image_width: 640",
                          "image_width: 640\nT_cam_base: [1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1, 0, 0, "
                          "0, 0, 1]")),
            "camera file 'cam.yaml': T_cam_base: the rotation part is not orthonormal (|R R^T - "
            "I| = 1.73)");
  EXPECT_EQ(error_of(with("image_width: 640",
                          "image_width: 640\nT_cam_base: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, 0, 0, "
                          "0, 0, 1]")),
            "camera file 'cam.yaml': T_cam_base: the rotation part is a reflection (determinant "
            "-1)");
  EXPECT_EQ(error_of(with("image_width: 640", "image_width: 640\nT_cam_base: [1, 0, 0]")),
            "camera file 'cam.yaml': T_cam_base: expected a 4x4 matrix, got 1x3");
  EXPECT_EQ(error_of(with("camera_matrix: !!opencv-matrix", "camera_matrix: [oops\nfoo: 1")),
            "camera file 'cam.yaml': not valid YAML at line 6: end of sequence flow not found");
  EXPECT_EQ(error_of("- 1\n- 2\n"), "camera file 'cam.yaml': the file must be a YAML map");
  EXPECT_EQ(error_of(std::string("left:\n") + "  image_width: 640\n"),
            "camera file 'cam.yaml': right: missing (a stereo file needs left and right)");
  EXPECT_EQ(error_of("left: 3\nright: 4\n"),
            "camera file 'cam.yaml': left: must be a map of image_width, image_height, "
            "camera_matrix, ...");
}

TEST(CameraFile, MissingFile) {
  Result<CameraFile> r = load_camera_file("/nonexistent/cam.yaml");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().message, "cannot open camera file '/nonexistent/cam.yaml'");
}

TEST(CameraFile, ShippedPumaStereoRigLoads) {
  Result<CameraFile> r = load_camera_file(test::data_path("cameras/puma560_stereo.yaml"));
  ASSERT_TRUE(r.ok()) << r.error().message;
  ASSERT_TRUE(r->is_stereo());
  EXPECT_TRUE(r->left_has_pose && r->right_has_pose);
  EXPECT_EQ(r->left.width, 640);
  EXPECT_EQ(r->left.height, 480);
  // The two optical centres are 6 cm apart.
  const Eigen::Vector3d left_centre = r->left.T_cam_base.inverse().translation();
  const Eigen::Vector3d right_centre = r->right->T_cam_base.inverse().translation();
  EXPECT_NEAR((left_centre - right_centre).norm(), 0.06, 1e-9);
}

// [SECTION] every format, every lens model

using ::testing::HasSubstr;

// A camera of each model with realistic coefficients.
CameraModel camera_of(DistortionModel model, double x) {
  CameraModel c = camera(x);
  switch (model) {
    case DistortionModel::plumb_bob:
      break;
    case DistortionModel::rational_polynomial:
      c.kc = *Distortion::from_coefficients(
          model, {0.41, -0.12, 0.0009, -0.0004, 0.013, 0.78, -0.05, 0.021});
      break;
    case DistortionModel::equidistant:
      c.alpha_c = 0.0;
      c.kc = *Distortion::from_coefficients(model, {-0.013, 0.0021, -0.0004, 0.00007});
      break;
  }
  return c;
}

constexpr DistortionModel kModels[] = {
    DistortionModel::plumb_bob, DistortionModel::rational_polynomial, DistortionModel::equidistant};

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

TEST(CameraFile, EveryModelRoundTripsThroughYamlXmlAndRos) {
  for (DistortionModel model : kModels) {
    SCOPED_TRACE(distortion_model_name(model));
    const CameraModel c = camera_of(model, 0.1);
    const std::size_t n = distortion_coefficient_count(model);
    for (const char* name : {"every.yaml", "every.xml"}) {
      SCOPED_TRACE(name);
      const std::string path = temp_path(name);
      ASSERT_TRUE(write_camera_file(c, path).ok());
      Result<CameraFile> read = load_camera_file(path);
      ASSERT_TRUE(read.ok()) << read.error().message;
      EXPECT_TRUE(read->left_has_pose);
      expect_same(read->left, c);
      // OpenCV reads the model's name and its D vector of 5, 8 or 4 values.
      cv::FileStorage fs(path, cv::FileStorage::READ);
      ASSERT_TRUE(fs.isOpened());
      EXPECT_EQ(static_cast<std::string>(fs["distortion_model"]), distortion_model_name(model));
      cv::Mat D;
      fs["distortion_coefficients"] >> D;
      EXPECT_EQ(D.total(), n);
      std::remove(path.c_str());
    }
    EXPECT_EQ(is_xml_text(opencv_camera_text(c, OpenCvStorageFormat::xml)), true);

    const std::string ros = ros_camera_info_yaml(c, "cam");
    EXPECT_THAT(ros, HasSubstr(std::string("distortion_model: ") + distortion_model_name(model)));
    EXPECT_THAT(ros, HasSubstr("cols: " + std::to_string(n)));
    Result<CameraFile> from_ros = parse_camera_yaml(ros, "ros.yaml");
    ASSERT_TRUE(from_ros.ok()) << from_ros.error().message;
    expect_same(from_ros->left, c);
    EXPECT_EQ(from_ros->left_name, "cam");
    ASSERT_TRUE(from_ros->left_rectification.has_value());
    EXPECT_TRUE(from_ros->left_rectification->R.isIdentity(0.0));
    EXPECT_EQ(from_ros->left_rectification->P(0, 2), c.cx);

    // A stereo file in XML.
    const StereoCameraModel pair{camera_of(model, 0.03), camera_of(model, -0.03)};
    const std::string stereo = temp_path("stereo.xml");
    ASSERT_TRUE(write_stereo_camera_file(pair, stereo).ok());
    EXPECT_TRUE(is_xml_text(read_text(stereo)));
    Result<CameraFile> two = load_camera_file(stereo);
    ASSERT_TRUE(two.ok()) << two.error().message;
    ASSERT_TRUE(two->is_stereo());
    expect_same(two->left, pair.left);
    expect_same(*two->right, pair.right);
    std::remove(stereo.c_str());
  }
}

TEST(CameraFile, XmlAsOpenCvWritesItByHand) {
  const char* xml = R"(<?xml version="1.0"?>
<opencv_storage>
<image_width>640</image_width>
<image_height>480</image_height>
<camera_matrix type_id="opencv-matrix">
  <rows>3</rows>
  <cols>3</cols>
  <dt>d</dt>
  <data>
    800. 0. 319.5 0. 800. 239.5 0. 0. 1.</data></camera_matrix>
<distortion_model>equidistant</distortion_model>
<distortion_coefficients type_id="opencv-matrix">
  <rows>4</rows>
  <cols>1</cols>
  <dt>d</dt>
  <data>
    -0.01 0.002 0. 0.</data></distortion_coefficients>
</opencv_storage>
)";
  Result<CameraFile> read = parse_camera_yaml(xml, "cam.xml");
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_FALSE(read->left_has_pose);
  EXPECT_EQ(read->left.kc.model, DistortionModel::equidistant);
  EXPECT_DOUBLE_EQ(read->left.kc.k2, 0.002);
  EXPECT_DOUBLE_EQ(read->left.cy, 239.5);

  // The YAML path's checks and messages, for XML too.
  auto without = [&xml](const std::string& from, const std::string& to = "") {
    std::string text = xml;
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
  };
  EXPECT_EQ(
      parse_camera_yaml(without("<image_width>640</image_width>\n"), "cam.xml").error().message,
      "camera file 'cam.xml': image_width: missing");
  EXPECT_EQ(parse_camera_yaml(without("-0.01 0.002 0. 0.", "-0.01 0.002 0. 0. 0."), "cam.xml")
                .error()
                .message,
            "camera file 'cam.xml': distortion_coefficients.data: expected 4 numbers (4x1), got 5");
  EXPECT_EQ(parse_camera_yaml(without("<rows>4</rows>\n  <cols>1</cols>\n  <dt>d</dt>\n  <data>\n"
                                      "    -0.01 0.002 0. 0.</data>",
                                      "<rows>5</rows>\n  <cols>1</cols>\n  <dt>d</dt>\n  <data>\n"
                                      "    -0.01 0.002 0. 0. 0.</data>"),
                              "cam.xml")
                .error()
                .message,
            "camera file 'cam.xml': distortion_coefficients: equidistant takes 4 coefficients "
            "(k1, k2, k3, k4), got 5");
  EXPECT_EQ(
      parse_camera_yaml(without("</image_height>", "</image_width>"), "cam.xml").error().message,
      "camera file 'cam.xml': not valid OpenCV FileStorage XML: line 4: Mismatched "
      "closing tag");
  EXPECT_EQ(parse_camera_yaml("<opencv_storage><image_width>640</image_width></opencv_storage>",
                              "cam.xml")
                .error()
                .message,
            "camera file 'cam.xml': not valid OpenCV FileStorage XML: unsupported layout "
            "(OpenCV's XML starts with <?xml version=\"1.0\"?> and <opencv_storage>)");

  const std::string path = temp_path("not_xml.xml");
  write_text(path, kMono);
  EXPECT_EQ(load_camera_file(path).error().message,
            "camera file '" + path +
                "': not valid OpenCV FileStorage XML: the text does not start with '<'");
  std::remove(path.c_str());
}

const char* kRos = R"(image_width: 640
image_height: 480
camera_name: narrow_stereo/left
camera_matrix:
  rows: 3
  cols: 3
  data: [533.0, 0.0, 341.5, 0.0, 533.1, 234.3, 0.0, 0.0, 1.0]
distortion_model: plumb_bob
distortion_coefficients:
  rows: 1
  cols: 5
  data: [-0.288, 0.097, 0.0011, -0.0003, 0.0]
rectification_matrix:
  rows: 3
  cols: 3
  data: [0.999, -0.0447, 0.0, 0.0447, 0.999, 0.0, 0.0, 0.0, 1.0]
projection_matrix:
  rows: 3
  cols: 4
  data: [510.2, 0.0, 330.0, 0.0, 0.0, 510.2, 240.1, 0.0, 0.0, 0.0, 1.0, 0.0]
)";

// Issue 25: OpenCV 4.6's in-memory FileStorage reader crashed on an XML camera file with a NUL
// byte in it (fuzz/crashes/camera_file/xml_nul_in_declaration.xml); it is refused first.
TEST(CameraFile, ANulByteInAnXmlFileIsRefusedBeforeOpenCvReadsIt) {
  const std::string text = std::string("<?xml version=") + '\0' + "\"1.0\"?>\n<opencv_storage/>\n";
  auto file = parse_camera_yaml(text, "nul.xml");
  ASSERT_FALSE(file);
  EXPECT_EQ(file.error().message,
            "camera file 'nul.xml': not valid OpenCV FileStorage XML: a NUL byte at offset 14");
}

// Issue 25: OpenCV allocates an opencv-matrix's rows x cols before reading its data; a camera
// file saying <cols>4294967288</cols> asked for 17 GB
// (fuzz/crashes/camera_file/xml_matrix_of_17_gigabytes.xml). Sizes over 1024 are refused first.
TEST(CameraFile, AMatrixLargerThanAnyCameraFileHoldsIsRefusedBeforeOpenCvAllocatesIt) {
  const std::string text =
      "<?xml version=\"1.0\"?>\n<opencv_storage>\n<camera_matrix type_id=\"opencv-matrix\">"
      "<rows>3</rows><cols>4294967288</cols><dt>d</dt><data>1 0 0</data></camera_matrix>\n"
      "</opencv_storage>\n";
  auto file = parse_camera_yaml(text, "huge.xml");
  ASSERT_FALSE(file);
  EXPECT_EQ(file.error().message,
            "camera file 'huge.xml': not valid OpenCV FileStorage XML: a matrix's cols is not a "
            "number from 0 to 1024");
  // fuzz/crashes/camera_file/xml_rows_not_a_number.xml: 48 GB.
  std::string question = text;
  question.replace(question.find("<rows>3"), 7, "<rows>?");
  file = parse_camera_yaml(question, "question.xml");
  ASSERT_FALSE(file);
  EXPECT_EQ(file.error().message,
            "camera file 'question.xml': not valid OpenCV FileStorage XML: a matrix's rows is not "
            "a number from 0 to 1024");
}

TEST(CameraFile, RosCameraInfoKeepsTheRectificationAndChecksIt) {
  Result<CameraFile> read = parse_camera_yaml(kRos, "left.yaml");
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_EQ(read->left_name, "narrow_stereo/left");
  ASSERT_TRUE(read->left_rectification.has_value());
  const Rectification& rect = *read->left_rectification;
  EXPECT_NEAR(rect.R(0, 1), -0.0447, 1e-3);  // snapped to the nearest rotation
  EXPECT_LT((rect.R * rect.R.transpose() - Eigen::Matrix3d::Identity()).norm(), 1e-12);
  EXPECT_EQ(rect.P(0, 0), 510.2);
  EXPECT_EQ(rect.P(1, 2), 240.1);
  EXPECT_DOUBLE_EQ(read->left.fx, 533.0);  // the raw camera's K is the intrinsics

  auto error = [](const std::string& from, const std::string& to) {
    std::string text = kRos;
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    Result<CameraFile> r = parse_camera_yaml(text.replace(at, from.size(), to), "left.yaml");
    EXPECT_FALSE(r.ok());
    return r.ok() ? "" : r.error().message;
  };
  EXPECT_EQ(error("distortion_model: plumb_bob", "distortion_model: kannala_brandt"),
            "camera file 'left.yaml': distortion_model: unknown distortion model "
            "'kannala_brandt' (expected plumb_bob, rational_polynomial or equidistant)");
  EXPECT_EQ(error("distortion_model: plumb_bob", "distortion_model: rational_polynomial"),
            "camera file 'left.yaml': distortion_coefficients: rational_polynomial takes 8 "
            "coefficients (k1, k2, p1, p2, k3, k4, k5, k6), got 5");
  EXPECT_EQ(error("distortion_model: plumb_bob", "distortion_model: equidistant"),
            "camera file 'left.yaml': distortion_coefficients: equidistant takes 4 coefficients "
            "(k1, k2, k3, k4), got 5");
  EXPECT_EQ(error("[0.999, -0.0447, 0.0, 0.0447, 0.999,", "[0.999, 0.5, 0.0, 0.0447, 0.999,"),
            "camera file 'left.yaml': rectification_matrix: the matrix is not orthonormal (|R "
            "R^T - I| = 0.809)");
  EXPECT_EQ(error("0.0, 0.0, 1.0]\nprojection", "0.0, 0.0, -1.0]\nprojection"),
            "camera file 'left.yaml': rectification_matrix: the matrix is a reflection "
            "(determinant -1)");
  EXPECT_EQ(error("  cols: 4\n  data: [510.2, 0.0, 330.0, 0.0, 0.0, 510.2, 240.1, 0.0, 0.0, 0.0, "
                  "1.0, 0.0]",
                  "  cols: 3\n  data: [510.2, 0.0, 330.0, 0.0, 510.2, 240.1, 0.0, 0.0, 1.0]"),
            "camera file 'left.yaml': projection_matrix: expected a 3x4 matrix, got 3x3");
  EXPECT_EQ(error("0.0, 0.0, 1.0, 0.0]", "0.0, 0.0, 1.0, 5.0]"),
            "camera file 'left.yaml': projection_matrix: the last row must be 0 0 1 0, got 0 0 "
            "1 5");
  EXPECT_EQ(error("[510.2, 0.0, 330.0", "[-510.2, 0.0, 330.0"),
            "camera file 'left.yaml': projection_matrix: fx' ([0][0]) must be positive");
  EXPECT_EQ(error("rectification_matrix:\n  rows: 3\n  cols: 3\n  data: [0.999, -0.0447, 0.0, "
                  "0.0447, 0.999, 0.0, 0.0, 0.0, 1.0]\n",
                  ""),
            "camera file 'left.yaml': rectification_matrix: missing (a ROS camera_info file "
            "gives rectification_matrix and projection_matrix together)");
}

// A stereo calibration of `model` as calibrate_stereo() leaves it: the cameras (right pose
// [R | T]), R, T and OpenCV's rectification for that model.
StereoCalibration stereo_calibration_of(DistortionModel model) {
  StereoCalibration c;
  c.cameras.left = camera_of(model, 0.0);
  c.cameras.right = camera_of(model, 0.0);
  c.cameras.right.fx = 815.25;
  c.cameras.right.cx = 322.1;
  c.cameras.left.alpha_c = c.cameras.right.alpha_c = 0.0;
  const Eigen::Isometry3d T_right_left =
      core::pose_from_xyz_rpy({-0.0612, 0.0021, -0.0013}, {0.011, -0.023, 0.004});
  c.cameras.left.T_cam_base = Eigen::Isometry3d::Identity();
  c.cameras.right.T_cam_base = T_right_left;
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) c.R(r, k) = T_right_left.linear()(r, k);
    c.T(r) = T_right_left.translation()(r);
  }
  const cv::Matx33d K1 = opencv_camera_matrix(c.cameras.left);
  const cv::Matx33d K2 = opencv_camera_matrix(c.cameras.right);
  const cv::Mat D1 = opencv_distortion(c.cameras.left.kc);
  const cv::Mat D2 = opencv_distortion(c.cameras.right.kc);
  cv::Mat R1, R2, P1, P2, Q;
  if (model == DistortionModel::equidistant) {
    cv::fisheye::stereoRectify(K1, D1, K2, D2, {640, 480}, c.R, c.T, R1, R2, P1, P2, Q,
                               cv::CALIB_ZERO_DISPARITY);
  } else {
    cv::stereoRectify(K1, D1, K2, D2, {640, 480}, c.R, c.T, R1, R2, P1, P2, Q,
                      cv::CALIB_ZERO_DISPARITY, 0.0);
  }
  c.rectification.R1 = cv::Matx33d(R1);
  c.rectification.R2 = cv::Matx33d(R2);
  c.rectification.P1 = cv::Matx34d(P1);
  c.rectification.P2 = cv::Matx34d(P2);
  c.rectification.Q = cv::Matx44d(Q);
  return c;
}

TEST(CameraFile, RosStereoPairKeepsItsBaselineForEveryModel) {
  for (DistortionModel model : kModels) {
    SCOPED_TRACE(distortion_model_name(model));
    const StereoCalibration c = stereo_calibration_of(model);
    const std::string l = temp_path("ros_left.yaml"), r = temp_path("ros_right.yaml");
    write_text(l, ros_stereo_camera_info_yaml(c, false, "left"));
    write_text(r, ros_stereo_camera_info_yaml(c, true, "right"));
    EXPECT_THAT(read_text(r),
                HasSubstr(std::string("distortion_model: ") + distortion_model_name(model)));

    for (const Result<CameraFile>& pair :
         {load_ros_stereo_pair(l, r), load_stereo_camera_files(l, r),
          load_camera_file(l + "," + r)}) {
      ASSERT_TRUE(pair.ok()) << pair.error().message;
      ASSERT_TRUE(pair->is_stereo());
      ASSERT_TRUE(pair->T_right_left.has_value());
      const Eigen::Isometry3d& T = *pair->T_right_left;
      Eigen::Matrix3d R;
      for (int i = 0; i < 3; ++i) {
        for (int k = 0; k < 3; ++k) R(i, k) = c.R(i, k);
      }
      EXPECT_LT((T.linear() - R).cwiseAbs().maxCoeff(), 1e-12);
      EXPECT_LT((T.translation() - Eigen::Vector3d(c.T(0), c.T(1), c.T(2))).norm(), 1e-9);
      EXPECT_NEAR(T.translation().norm(), c.baseline(), 1e-9);
      // Calibrated, not registered: the left camera is the base frame.
      EXPECT_FALSE(pair->left_has_pose || pair->right_has_pose);
      EXPECT_TRUE(pair->left.T_cam_base.isApprox(Eigen::Isometry3d::Identity()));
      EXPECT_TRUE(pair->right->T_cam_base.isApprox(T));
      expect_same(pair->left, c.cameras.left);
      EXPECT_EQ(pair->right->kc.coefficients(), c.cameras.right.kc.coefficients());
      EXPECT_EQ(pair->left_name, "left");
      EXPECT_EQ(pair->right_name, "right");
    }
    // What registration reads for --rig left.yaml,right.yaml.
    const auto geometry = load_stereo_geometry(l + "," + r);
    ASSERT_TRUE(geometry.ok()) << geometry.error().message;
    EXPECT_LT(cv::norm(geometry->R - c.R), 1e-12);
    EXPECT_LT(cv::norm(geometry->T - c.T), 1e-9);
    std::remove(l.c_str());
    std::remove(r.c_str());
  }
}

TEST(CameraFile, RosStereoPairErrorsSayWhatIsWrong) {
  const StereoCalibration c = stereo_calibration_of(DistortionModel::plumb_bob);
  const std::string l = temp_path("bad_left.yaml"), r = temp_path("bad_right.yaml");
  const std::string other = temp_path("bad_other.yaml");
  const std::string pair = "stereo pair '" + l + "', '" + other + "': ";
  write_text(l, ros_stereo_camera_info_yaml(c, false, "left"));
  write_text(r, ros_stereo_camera_info_yaml(c, true, "right"));

  // The right file of another size, of another model.
  StereoCalibration resized = c;
  resized.cameras.right.width = 800;
  write_text(other, ros_stereo_camera_info_yaml(resized, true, "right"));
  EXPECT_EQ(load_stereo_camera_files(l, other).error().message,
            pair +
                "the two files disagree in image size: left 640x480, right 800x480 (one "
                "rectified pair has one image size)");
  StereoCalibration fisheye = c;
  fisheye.cameras.right.kc = camera_of(DistortionModel::equidistant, 0.0).kc;
  write_text(other, ros_stereo_camera_info_yaml(fisheye, true, "right"));
  EXPECT_EQ(load_camera_file(l + "," + other).error().message,
            pair +
                "the two files disagree in distortion_model: left plumb_bob, right "
                "equidistant");

  // Two mono camera_info files: P = [K | 0] on the right too, no baseline.
  MonoCalibration mono;
  mono.camera = c.cameras.right;
  write_text(other, ros_mono_camera_info_yaml(mono, "right"));
  EXPECT_EQ(load_stereo_camera_files(l, other).error().message,
            pair +
                "right: projection_matrix: Tx = P[0][3] is 0, so the pair has no baseline (a "
                "rectified right camera has Tx = -fx' * B, B the baseline in metres); is it a "
                "mono camera_info file?");
  const auto geometry = load_stereo_geometry(l + "," + other);
  EXPECT_THAT(geometry.error().message, HasSubstr("so the pair has no baseline"));

  // Swapped files.
  EXPECT_THAT(load_stereo_camera_files(r, l).error().message,
              HasSubstr("left: projection_matrix: Tx = P[0][3] = "));
  EXPECT_THAT(load_stereo_camera_files(r, l).error().message,
              HasSubstr("must be 0 for the left camera of a pair (are the two files swapped?)"));

  // A right camera rectified with another focal length: not one pair.
  StereoCalibration refocused = c;
  refocused.rectification.P2(0, 0) *= 1.01;
  write_text(other, ros_stereo_camera_info_yaml(refocused, true, "right"));
  EXPECT_THAT(load_stereo_camera_files(l, other).error().message,
              HasSubstr("right: projection_matrix: fx' ([0][0]) = "));

  // load_ros_stereo_pair insists on camera_info files.
  write_text(other, opencv_camera_yaml(c.cameras.right));
  EXPECT_EQ(load_ros_stereo_pair(l, other).error().message,
            "camera file '" + other +
                "': rectification_matrix and projection_matrix: missing (not a ROS camera_info "
                "file of a stereo pair)");
  // ... which an OpenCV pair of files is not, and loads as before (no geometry).
  const auto plain = load_stereo_camera_files(l, other);
  ASSERT_TRUE(plain.ok()) << plain.error().message;
  EXPECT_FALSE(plain->T_right_left.has_value());
  for (const std::string& p : {l, r, other}) std::remove(p.c_str());
}

TEST(CameraFile, CalibrationWritersEmitEveryModelInYamlAndXml) {
  for (DistortionModel model : kModels) {
    SCOPED_TRACE(distortion_model_name(model));
    const StereoCalibration c = stereo_calibration_of(model);
    const CalibrationPattern pattern = *parse_calibration_pattern("chessboard:9x6:0.03");
    MonoCalibration mono;
    mono.camera = c.cameras.left;
    mono.camera.T_cam_base = Eigen::Isometry3d::Identity();
    for (const char* extension : {".yaml", ".xml"}) {
      SCOPED_TRACE(extension);
      const std::string stereo = temp_path(std::string("calibration_stereo") + extension);
      const std::string single = temp_path(std::string("calibration_mono") + extension);
      ASSERT_TRUE(write_files_atomically({{stereo, stereo_calibration_yaml(c, pattern)},
                                          {single, mono_calibration_yaml(mono, pattern)}})
                      .ok());
      EXPECT_EQ(is_xml_text(read_text(stereo)), std::string(extension) == ".xml");
      EXPECT_EQ(is_xml_text(read_text(single)), std::string(extension) == ".xml");

      const auto file = load_camera_file(stereo);
      ASSERT_TRUE(file.ok()) << file.error().message;
      ASSERT_TRUE(file->is_stereo());
      EXPECT_FALSE(file->left_has_pose);
      EXPECT_EQ(file->left.kc.model, model);
      EXPECT_EQ(file->right->kc.coefficients(), c.cameras.right.kc.coefficients());
      ASSERT_TRUE(file->T_right_left.has_value());  // the file's R and T
      EXPECT_LT((file->T_right_left->matrix() - c.cameras.right.T_cam_base.matrix())
                    .cwiseAbs()
                    .maxCoeff(),
                1e-12);
      const auto geometry = load_stereo_geometry(stereo);
      ASSERT_TRUE(geometry.ok()) << geometry.error().message;
      EXPECT_LT(cv::norm(geometry->T - c.T), 1e-15);

      const auto one = load_camera_file(single);
      ASSERT_TRUE(one.ok()) << one.error().message;
      expect_same(one->left, mono.camera);
      cv::FileStorage fs(single, cv::FileStorage::READ);
      EXPECT_EQ(static_cast<std::string>(fs["distortion_model"]), distortion_model_name(model));
      EXPECT_EQ(static_cast<std::string>(fs["calibration_pattern"]), "chessboard:9x6:0.03");
      cv::Mat D;
      fs["distortion_coefficients"] >> D;
      EXPECT_EQ(D.total(), distortion_coefficient_count(model));
      std::remove(stereo.c_str());
      std::remove(single.c_str());
    }
    const std::string ros = ros_mono_camera_info_yaml(mono, "camera");
    EXPECT_THAT(ros, HasSubstr(std::string("distortion_model: ") + distortion_model_name(model)));
    const auto from_ros = parse_camera_yaml(ros, "camera.yaml");
    ASSERT_TRUE(from_ros.ok()) << from_ros.error().message;
    expect_same(from_ros->left, mono.camera);
  }
}

}  // namespace
}  // namespace telear::vision
